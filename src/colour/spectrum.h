// Spectra and CIE 1931 colorimetry: how radiance computed at a few wavelengths
// becomes colour, only at display (Cohen & Wallace §9.5; CIE 1931 2° observer;
// IEC 61966-2-1).
//
// A spectral scene runs the solution and every renderer at its sample
// wavelengths (docs/spectral.md). Between the samples the radiance is taken as
// piecewise linear, the way the Cornell Box Data spectra are published
// (graphics.cornell.edu/online/box/data.html), and integrated against the CIE
// 1931 2° colour-matching functions (1-nm table) over the samples' range.
// Values are relative to an equal-energy white: XYZ is divided by ∫ȳ over the
// same range, so a constant spectrum v has Y = v — the same luminance as an RGB
// value (v, v, v) — and luminance in cd/m² is 683·Y.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "util/math.h"

namespace radiant {

/// A spectrum given at sample wavelengths: piecewise linear between them and
/// held constant beyond the first and the last (the Cornell Box Data's
/// convention).
struct SampledSpectrum {
  std::vector<double> wavelengths;  ///< nm, strictly increasing, at least one sample
  std::vector<double> values;       ///< one per wavelength

  /// The value at a wavelength in nm.
  double at(double wavelengthNm) const;
};

/// The CIE table's range, nm (1-nm steps).
constexpr int kCieFirstWavelength = 360;
constexpr int kCieLastWavelength = 830;

/// CIE 1931 2° standard observer (x̄, ȳ, z̄) at an integer wavelength in nm
/// (CIE 015 1-nm table, as distributed by CVRL); zero outside 360–830 nm.
Vec3 cieColourMatching(int wavelengthNm);

/// Σ ȳ(λ) over the integers λ in [first, last] nm: ∫ȳ dλ with 1-nm steps.
double cieYIntegral(int first, int last);

/// XYZ of a spectrum relative to an equal-energy illuminant over [first, last]
/// nm: X = Σ S x̄ / Σ ȳ, Y = Σ S ȳ / Σ ȳ, Z = Σ S z̄ / Σ ȳ, sums over the
/// integer wavelengths in the range (CIE 015's relative form; the Cornell
/// reflectances' colours in docs/spectral.md use 400–700).
Vec3 spectrumToXyz(const SampledSpectrum &spectrum, int first = 400, int last = 700);

/// CIE XYZ → linear sRGB (Rec.709 primaries, D65 white with Y = 1), IEC 61966-2-1.
Vec3 xyzToLinearSrgb(const Vec3 &xyz);
/// Linear sRGB → CIE XYZ, the inverse of xyzToLinearSrgb.
Vec3 linearSrgbToXyz(const Vec3 &rgb);

/// (x, y) chromaticity of an XYZ colour; (0, 0) for black.
std::array<double, 2> chromaticity(const Vec3 &xyz);

/// A 3×3 matrix as three rows.
using Matrix3 = std::array<Vec3, 3>;
inline Vec3 operator*(const Matrix3 &m, const Vec3 &v) {
  return {dot(m[0], v), dot(m[1], v), dot(m[2], v)};
}
Matrix3 operator*(const Matrix3 &a, const Matrix3 &b);

/// XYZ of the D65 white with Y = 1, from its chromaticity (0.3127, 0.3290),
/// the white the xyzToLinearSrgb matrix maps to (1, 1, 1).
constexpr Vec3 kD65White{0.3127 / 0.3290, 1.0, (1.0 - 0.3127 - 0.3290) / 0.3290};

/// Bradford chromatic adaptation (von Kries scaling of the Bradford cone
/// responses; Lam 1985, as in ICC v4): XYZ seen under `sourceWhite` → the
/// corresponding XYZ under `destinationWhite`. Maps sourceWhite to destinationWhite exactly.
Matrix3 bradfordAdaptation(const Vec3 &sourceWhite, const Vec3 &destinationWhite);

/// Whether an equal-energy white is shown as the display's white.
enum class WhiteBalance {
  None,  ///< no adaptation: XYZ → sRGB as is (docs/spectral.md's colours); a constant spectrum looks slightly pink
  EqualEnergy,  ///< Bradford adaptation of the bands' equal-energy white to D65: a constant spectrum is grey
};

/// How radiance at a scene's sample wavelengths becomes colour. Band i's value
/// stands for a tent (hat) function peaking at wavelength i and falling to
/// zero at its neighbours, so the spectrum is piecewise linear through the
/// samples and zero outside [first, last]; XYZ = Σ_i weight_i · value_i with
/// weight_i = Σ_λ tent_i(λ) (x̄, ȳ, z̄)(λ) / Σ_λ ȳ(λ) over the integer λ in
/// [first sample, last sample]. For a spectrum sampled at integer band
/// wavelengths this equals spectrumToXyz over the same range exactly.
class BandColourMatching {
 public:
  /// `wavelengths` in nm: at least 2, strictly increasing, within 360–830 nm.
  /// Throws std::invalid_argument otherwise.
  explicit BandColourMatching(std::vector<double> wavelengths);

  int bandCount() const { return int(wavelengths_.size()); }
  const std::vector<double> &wavelengths() const { return wavelengths_; }

  /// XYZ weight of band i.
  const Vec3 &xyzWeight(int band) const { return xyzWeights_[band]; }
  /// XYZ of band values (one per band).
  Vec3 toXyz(std::span<const double> values) const;
  /// Linear sRGB weight of each band: sRGB = Σ_i weight_i · value_i, with the white balance folded in.
  std::vector<Vec3> linearSrgbWeights(WhiteBalance balance) const;
  /// XYZ of the constant spectrum 1 over the bands (Y = 1): the white that EqualEnergy maps to D65.
  Vec3 equalEnergyWhite() const;

 private:
  std::vector<double> wavelengths_;
  std::vector<Vec3> xyzWeights_;
};

}  // namespace radiant
