// Luminous intensity distributions of luminaires, read from photometric
// files: IES LM-63 (-1995, -2002, -2019) and EULUMDAT (docs/luminaires.md).
//
// A photometric file tabulates a luminaire's luminous intensity I_v (cd)
// over a web of angles measured around it (photometric types C, B and A of
// IES LM-63; EULUMDAT is type C). Radiant keeps the table, expanded to a
// full web where the file gives only a symmetric part, and answers
// I_v(direction) by bilinear interpolation in the two angles, in the
// luminaire's own frame:
//
//   local = (x, y, z) with z along the photometric axis ("aim" in the scene:
//   type C's nadir γ = 0, the beam axis H = V = 0 of types A and B), x the
//   direction of the C = 0 half-plane (type C), y that of C = 90°.
//
// so type C's angles are γ = acos z, C = atan2(y, x). The mapping of types A
// and B onto (x, y, z) is in docs/luminaires.md.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "util/error.h"
#include "util/math.h"

namespace radiant {

enum class PhotometricType { C, B, A };

class PhotometricDistribution {
 public:
  /// Luminous intensity, cd, towards the unit direction `local` of the
  /// luminaire's frame (above); every multiplier of the file applied
  /// (candela multiplier, ballast factor; for EULUMDAT cd/klm × lamp flux /
  /// 1000 × conversion factor), but not the tilt factor.
  double candela(const Vec3 &local) const;
  /// IES TILT: the lamp output factor when the luminaire is tilted by
  /// `degrees` from the orientation it was measured in (photometric axis
  /// straight down), interpolated in the file's table; 1 without a table.
  double tiltFactor(double degrees) const;
  /// Luminous flux ∫ I_v dω over the sphere, lm, of the interpolated
  /// distribution candela() answers.
  double lumens() const { return lumens_; }
  /// The largest intensity in the table, cd.
  double maxCandela() const { return maxCandela_; }
  /// A direction of the luminaire's frame drawn with a density (per steradian,
  /// `pdf`) proportional to a piecewise-constant bound of candela(): every
  /// direction with candela() > 0 has pdf > 0. u1, u2 uniform in [0, 1).
  Vec3 sample(double u1, double u2, double &pdf) const;
  /// Density of sample() at `local`, per steradian.
  double pdf(const Vec3 &local) const;

  PhotometricType type() const { return type_; }
  /// What the file says it is (the luminaire's name, manufacturer, lamp), for reports.
  const std::string &description() const { return description_; }
  /// Where it was read from.
  const std::string &file() const { return file_; }

  // Construction is by the readers below; fields are public to them through
  // this friend function (the distribution is immutable once read).
  friend class PhotometricBuilder;

 private:
  PhotometricType type_ = PhotometricType::C;
  std::string description_, file_;
  double lumens_ = 0, maxCandela_ = 0;
  // The expanded web, in spherical angles about the type's own polar axis
  // (photometry.cpp, docs/luminaires.md): azimuth φ and polar angle θ, both
  // increasing; type C's web spans a whole turn of φ and wraps.
  std::vector<double> azimuthRadians_, polarRadians_;
  bool azimuthWraps_ = false;
  std::vector<double> candela_;  ///< [a · polarRadians_.size() + p]
  /// Per cell [a · (polarRadians_.size() − 1) + p]: the cumulative share of
  /// sample()'s draws, and its density (per steradian) in that cell.
  std::vector<double> sampleCdf_, samplePdf_;
  std::vector<double> tiltDegrees_, tiltFactors_;  ///< empty: TILT=NONE

  /// The cell of the web holding `local` and the fractions along its two
  /// angles; false where the web has no data (candela 0).
  bool locate(const Vec3 &local, size_t &azimuthCell, size_t &polarCell, double &azimuthFraction,
              double &polarFraction) const;
};

/// Reads an IES LM-63 file (1995, 2002 or 2019; TILT=NONE, INCLUDE or a
/// tilt file beside it). Errors name the file and line.
std::shared_ptr<const PhotometricDistribution> readIesFile(const std::string &path);
/// Reads a EULUMDAT (.ldt) file. Errors name the file and line.
std::shared_ptr<const PhotometricDistribution> readEulumdatFile(const std::string &path);
/// By extension: .ies → IES, .ldt → EULUMDAT; anything else is refused.
std::shared_ptr<const PhotometricDistribution> readPhotometricFile(const std::string &path);

/// What a photometric file is by its content, whatever its name: Ies for a
/// file with a TILT= line (every LM-63 version has one before its numbers)
/// or an IESNA first line; Eulumdat for one without, whose lines 2 to 6 are
/// EULUMDAT's type (0–3), symmetry (0–4), C-plane count, C-plane distance and
/// intensity count; Unknown otherwise (a damaged file: its reader says why).
enum class PhotometricFormat { Ies, Eulumdat, Unknown };
PhotometricFormat photometricFormatOf(std::string_view text);
/// photometricFormatOf the first 64 KiB of the file at `path` (Unknown when it cannot be read).
PhotometricFormat photometricFormatOfFile(const std::string &path);

}  // namespace radiant
