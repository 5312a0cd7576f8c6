// What the photometric readers (ies_file.cpp, eulumdat_file.cpp) share: the
// builder they fill with the table as the file gives it, the bounded reading
// of a file, and a cursor over its lines and numbers that knows line numbers.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "scene/photometry.h"

namespace radiant {

/// Limits on what a photometric file may ask for, checked before allocating.
constexpr uintmax_t kMaxPhotometricFileBytes = uintmax_t(64) << 20;
constexpr int64_t kMaxPhotometricAnglesPerAxis = 10000;
constexpr int64_t kMaxPhotometricValues = 1000000;

/// A distribution as a file states it, before its symmetric part is expanded
/// to a full web (photometry.cpp).
class PhotometricBuilder {
 public:
  PhotometricType type = PhotometricType::C;
  std::string file, description;
  /// The file's angles, strictly increasing (the readers check that, with
  /// line numbers), and its intensities in cd with every multiplier applied:
  /// candela[h · verticalDegrees.size() + v].
  std::vector<double> horizontalDegrees, verticalDegrees, candela;
  /// Where the angle lists start, for errors about their range or symmetry.
  InputLocation horizontalAt, verticalAt;
  std::vector<double> tiltDegrees, tiltFactors;

  /// Checks the angles' ranges against the type's rules, expands the symmetry
  /// they imply and computes the flux and sampling tables. Throws InputError.
  std::shared_ptr<const PhotometricDistribution> build() const;
};

namespace photometry_detail {

/// The whole file, refused when it cannot be read or exceeds 64 MiB.
/// `format` names it in messages ("IES", "EULUMDAT", "IES tilt").
std::string readBoundedFile(const std::string &path, const std::string &format, const InputLocation &from);

/// Lines (LF, CRLF or CR ends) and, within them, numbers separated by
/// whitespace and commas, with the 1-based line each came from.
class TextCursor {
 public:
  TextCursor(std::string file, std::string_view text);
  /// The next whole line, without its end; false at the end of the text.
  bool nextLine(std::string_view &line);
  /// The next token, crossing line ends; false at the end of the text.
  bool nextToken(std::string_view &token);
  /// The line of what was read last (the last line at the end of the text).
  int line() const { return line_; }
  const std::string &file() const { return file_; }
  InputLocation here() const { return {file_, line_, 0, ""}; }

  /// The next number, without building a message: what loops over many
  /// values use, throwing with their own message on End or Bad.
  enum class Read { Ok, End, Bad };
  Read decimal(double &value, std::string_view &token);

  /// A number where `what` is expected ("the candela multiplier"); the
  /// errors name the line and `what`, and show what was found instead.
  double decimal(const std::string &what);
  int64_t integer(const std::string &what);
  /// Throws unless only whitespace (and a DOS end-of-file mark) is left.
  void expectEnd(const std::string &after);

 private:
  std::string file_;
  std::string_view text_, rest_;  ///< all of it; the unread part of the current line
  size_t next_ = 0;               ///< where the next line starts
  int line_ = 0;
  bool inLine_ = false;
};

/// `count` angles in degrees, strictly increasing and within [low, high];
/// `name` says what they are in messages ("vertical angle"). `firstAt` gets
/// the location of the first.
std::vector<double> readAngles(TextCursor &in, int64_t count, const std::string &name, double low, double high,
                               InputLocation &firstAt);
/// `count` intensities (finite, ≥ 0) times `scale`, appended to `out`;
/// `name` says what they are in messages ("candela value").
void readIntensities(TextCursor &in, int64_t count, double scale, const std::string &name, std::vector<double> &out);

/// `text` quoted for a message: at most 24 characters, unprintable bytes as '?'.
std::string quoted(std::string_view text);
std::string_view trim(std::string_view text);

}  // namespace photometry_detail
}  // namespace radiant
