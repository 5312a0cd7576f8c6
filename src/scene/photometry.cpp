// Luminous intensity distributions (docs/luminaires.md#photometric-files):
// the expansion of a file's symmetric table to a full web, bilinear
// interpolation in its two angles, the flux of exactly that interpolant, and
// sampling of directions from a piecewise-constant bound of it.
//
// Every photometric type is kept in one parameterisation: spherical angles
// about the type's own polar axis, azimuth φ and polar angle θ, so that
// dω = sin θ dθ dφ for all three:
//
//   type C: polar axis +z (nadir), θ = γ, φ = C from +x towards +y;
//   type B: polar axis −y (the horizontal axis the B planes share),
//           θ = H + 90°, φ = V from +z towards +x;
//   type A: polar axis −x (the vertical axis the A planes share),
//           θ = V + 90°, φ = H from +z towards +y.
//
// Bilinear interpolation in (φ, θ) is then integrated cell by cell in closed
// form (∫ sin θ and ∫ θ sin θ), so lumens() is the flux of candela() to
// rounding.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "scene/photometry_detail.h"
#include "util/file_extension.h"
#include "util/input_file.h"
#include "util/parse_number.h"

namespace radiant {
namespace {

constexpr double kRadiansPerDegree = kPi / 180;
/// Angles that the symmetry rules compare (0, 90, 180, 270, 360) match within this, in degrees.
constexpr double kAngleTolerance = 1e-6;

bool near(double a, double b) {
  return std::abs(a - b) <= kAngleTolerance;
}

void anglesOf(PhotometricType type, const Vec3 &d, double &azimuth, double &polar) {
  switch (type) {
    case PhotometricType::C:
      polar = std::acos(std::clamp(d.z, -1.0, 1.0));
      azimuth = std::atan2(d.y, d.x);
      break;
    case PhotometricType::B:
      polar = std::acos(std::clamp(-d.y, -1.0, 1.0));
      azimuth = std::atan2(d.x, d.z);
      break;
    case PhotometricType::A:
      polar = std::acos(std::clamp(-d.x, -1.0, 1.0));
      azimuth = std::atan2(d.y, d.z);
      break;
  }
}

Vec3 directionOf(PhotometricType type, double azimuth, double cosPolar) {
  double sinPolar = std::sqrt(std::max(0.0, 1 - cosPolar * cosPolar));
  double c = std::cos(azimuth), s = std::sin(azimuth);
  switch (type) {
    case PhotometricType::C:
      return {sinPolar * c, sinPolar * s, cosPolar};
    case PhotometricType::B:
      return {sinPolar * s, -cosPolar, sinPolar * c};
    case PhotometricType::A:
      return {-cosPolar, sinPolar * s, sinPolar * c};
  }
  return {0, 0, 1};
}

/// One axis of the expanded web: its angles (degrees) and, for each, the index
/// of the file's angle whose intensities it repeats.
struct ExpandedAxis {
  std::vector<double> degrees;
  std::vector<size_t> source;
  void add(double angle, size_t from) {
    degrees.push_back(angle);
    source.push_back(from);
  }
};

std::string degreesText(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

/// Type C's horizontal angles (LM-63-2002 §4.19; EULUMDAT's Isym give the same
/// sets): {a} alone is rotationally symmetric; 0…90 one quadrant of a
/// distribution symmetric about both the C0–C180 and the C90–C270 planes;
/// 0…180 a half symmetric about the C0–C180 plane; 90…270 a half symmetric
/// about the C90–C270 plane (LM-63-1995); 0…(180, 360] the whole turn, the
/// gap up to 360 interpolated towards C0. The result spans exactly one turn.
ExpandedAxis expandTypeCHorizontal(std::vector<double> a, const InputLocation &where) {
  ExpandedAxis axis;
  const size_t n = a.size();
  // The ends the rules name are taken as exactly those angles, so that mirrored copies stay in order.
  for (double exact : {0.0, 90.0, 180.0, 270.0, 360.0}) {
    if (near(a.front(), exact)) a.front() = exact;
    if (near(a.back(), exact)) a.back() = exact;
  }
  const double first = a.front(), last = a.back();
  if (n == 1) {
    axis.add(first, 0);
    axis.add(first + 360, 0);
    return axis;
  }
  for (size_t i = 0; i < n; ++i) axis.add(a[i], i);
  if (near(first, 0) && near(last, 90)) {
    for (size_t i = n - 1; i-- > 0;) axis.add(180 - a[i], i);
    for (size_t i = 1; i < n; ++i) axis.add(180 + a[i], i);
    for (size_t i = n - 1; i-- > 0;) axis.add(360 - a[i], i);
  } else if (near(first, 0) && near(last, 180)) {
    for (size_t i = n - 1; i-- > 0;) axis.add(360 - a[i], i);
  } else if (near(first, 90) && near(last, 270)) {
    for (size_t i = n - 1; i-- > 0;) axis.add(540 - a[i], i);  // C → 180° − C, one turn on
  } else if (near(first, 0) && last > 180 && last <= 360 + kAngleTolerance) {
    if (!near(last, 360)) axis.add(360, 0);
  } else {
    throw InputError(where, "type C horizontal angles from " + degreesText(first) + " to " + degreesText(last) +
                                ": expected 0 alone (rotational symmetry), 0 to 90 (quadrants), 0 to 180 or 90 to "
                                "270 (bilateral symmetry), or 0 to more than 180 and at most 360");
  }
  axis.degrees.back() = axis.degrees.front() + 360;  // exactly one turn, whatever the rounding
  return axis;
}

/// Types A and B: an axis from −90 (or 0: symmetric about 0, mirrored) to at most 90.
ExpandedAxis expandTypeABAxis(std::vector<double> a, const InputLocation &where, const std::string &name) {
  const size_t n = a.size();
  for (double exact : {-90.0, 0.0, 90.0}) {
    if (near(a.front(), exact)) a.front() = exact;
    if (near(a.back(), exact)) a.back() = exact;
  }
  if (n < 2) throw InputError(where, "expected at least two " + name + " angles (types A and B)");
  if (a.front() < -90 - kAngleTolerance || a.back() > 90 + kAngleTolerance || a.front() > kAngleTolerance)
    throw InputError(where, name + " angles from " + degreesText(a.front()) + " to " + degreesText(a.back()) +
                                ": types A and B expect them to start at -90 or at 0 (symmetric about 0) and "
                                "to end at 90 at most");
  ExpandedAxis axis;
  if (near(a.front(), 0))
    for (size_t i = n; i-- > 1;) axis.add(-a[i], i);
  for (size_t i = 0; i < n; ++i) axis.add(a[i], i);
  return axis;
}

/// ∫ (1 − s) sin θ dθ and ∫ s sin θ dθ over [θ0, θ1], s = (θ − θ0)/(θ1 − θ0):
/// the weights of a cell's two polar corners in the flux of the interpolant.
void polarWeights(double theta0, double theta1, double &w0, double &w1) {
  double width = theta1 - theta0;
  double total = std::cos(theta0) - std::cos(theta1);
  w1 = 2 * std::cos(0.5 * (theta0 + theta1)) * std::sin(0.5 * width) / width - std::cos(theta1);
  // Both are ≥ 0; the subtraction can round a sliver cell's to −1e-17.
  w1 = std::clamp(w1, 0.0, total);
  w0 = total - w1;
}

}  // namespace

std::shared_ptr<const PhotometricDistribution> PhotometricBuilder::build() const {
  const size_t nh = horizontalDegrees.size(), nv = verticalDegrees.size();
  if (nh == 0 || nv == 0 || candela.size() != nh * nv)
    throw InputError({file, 0, 0, ""}, "the photometric table is empty or does not match its angle counts");
  ExpandedAxis azimuth, polar;
  bool azimuthFromHorizontal = true;
  if (type == PhotometricType::C) {
    if (nv < 2) throw InputError(verticalAt, "expected at least two vertical angles");
    if (verticalDegrees.front() < -kAngleTolerance || verticalDegrees.back() > 180 + kAngleTolerance)
      throw InputError(verticalAt, "type C vertical angles from " + degreesText(verticalDegrees.front()) + " to " +
                                       degreesText(verticalDegrees.back()) + ": expected them within 0 to 180");
    azimuth = expandTypeCHorizontal(horizontalDegrees, horizontalAt);
    for (size_t i = 0; i < nv; ++i) polar.add(std::clamp(verticalDegrees[i], 0.0, 180.0), i);
  } else {
    ExpandedAxis h = expandTypeABAxis(horizontalDegrees, horizontalAt, "horizontal");
    ExpandedAxis v = expandTypeABAxis(verticalDegrees, verticalAt, "vertical");
    // Type A: planes about the vertical axis, H their azimuth and V the latitude
    // within them; type B: planes about a horizontal axis, V the azimuth, H the latitude.
    azimuthFromHorizontal = type == PhotometricType::A;
    azimuth = azimuthFromHorizontal ? h : v;
    polar = azimuthFromHorizontal ? v : h;
    for (double &theta : polar.degrees) theta = std::clamp(theta + 90, 0.0, 180.0);
  }

  // Angles a hair apart (within kAngleTolerance of a snapped end) would make
  // empty or reversed cells.
  for (const ExpandedAxis *axis : {&azimuth, &polar})
    for (size_t k = 1; k < axis->degrees.size(); ++k)
      if (!(axis->degrees[k] > axis->degrees[k - 1]))
        throw InputError(axis == &azimuth ? (azimuthFromHorizontal ? horizontalAt : verticalAt)
                                          : (azimuthFromHorizontal ? verticalAt : horizontalAt),
                         "angles closer together than " + degreesText(kAngleTolerance) +
                             " degrees at the ends of the list: expected increasing angles");

  auto d = std::make_shared<PhotometricDistribution>();
  d->type_ = type;
  d->file_ = file;
  d->description_ = description;
  d->tiltDegrees_ = tiltDegrees;
  d->tiltFactors_ = tiltFactors;
  d->azimuthWraps_ = type == PhotometricType::C;
  const size_t na = azimuth.degrees.size(), np = polar.degrees.size();
  for (double a : azimuth.degrees) d->azimuthRadians_.push_back(a * kRadiansPerDegree);
  for (double p : polar.degrees) d->polarRadians_.push_back(p * kRadiansPerDegree);
  d->candela_.resize(na * np);
  for (size_t i = 0; i < na; ++i)
    for (size_t j = 0; j < np; ++j) {
      size_t h = azimuthFromHorizontal ? azimuth.source[i] : polar.source[j];
      size_t v = azimuthFromHorizontal ? polar.source[j] : azimuth.source[i];
      d->candela_[i * np + j] = candela[h * nv + v];
    }
  for (double c : candela) d->maxCandela_ = std::max(d->maxCandela_, c);

  // Flux of the bilinear interpolant, cell by cell, and the sampling bound:
  // each cell's largest corner (bilinear interpolation never exceeds it).
  const std::vector<double> &phi = d->azimuthRadians_, &theta = d->polarRadians_;
  d->sampleCdf_.assign((na - 1) * (np - 1), 0.0);
  d->samplePdf_.assign((na - 1) * (np - 1), 0.0);
  double lumens = 0, boundFlux = 0;
  for (size_t i = 0; i + 1 < na; ++i) {
    double width = phi[i + 1] - phi[i];
    for (size_t j = 0; j + 1 < np; ++j) {
      double w0, w1;
      polarWeights(theta[j], theta[j + 1], w0, w1);
      const double *c0 = &d->candela_[i * np + j], *c1 = &d->candela_[(i + 1) * np + j];
      lumens += 0.5 * width * ((c0[0] + c1[0]) * w0 + (c0[1] + c1[1]) * w1);
      double bound = std::max({c0[0], c0[1], c1[0], c1[1]});
      size_t cell = i * (np - 1) + j;
      d->samplePdf_[cell] = bound;
      boundFlux += bound * width * (std::cos(theta[j]) - std::cos(theta[j + 1]));
      d->sampleCdf_[cell] = boundFlux;
    }
  }
  d->lumens_ = lumens;
  if (boundFlux > 0) {
    for (double &c : d->sampleCdf_) c /= boundFlux;
    for (double &p : d->samplePdf_) p /= boundFlux;
    d->sampleCdf_.back() = 1;
  }
  return d;
}

bool PhotometricDistribution::locate(const Vec3 &local, size_t &azimuthCell, size_t &polarCell, double &azimuthFraction,
                                     double &polarFraction) const {
  if (candela_.empty() || !isFinite(local)) return false;
  double len = length(local);
  if (!(len > 0)) return false;
  double phi = 0, theta = 0;
  anglesOf(type_, local / len, phi, theta);
  const std::vector<double> &a = azimuthRadians_, &p = polarRadians_;
  if (azimuthWraps_) {
    double turns = std::fmod(phi - a.front(), 2 * kPi);
    if (turns < 0) turns += 2 * kPi;
    phi = std::min(a.front() + turns, a.back());
  } else if (phi < a.front() || phi > a.back()) {
    return false;
  }
  if (theta < p.front() || theta > p.back()) return false;
  azimuthCell = std::min<size_t>(std::upper_bound(a.begin(), a.end(), phi) - a.begin(), a.size() - 1) - 1;
  polarCell = std::min<size_t>(std::upper_bound(p.begin(), p.end(), theta) - p.begin(), p.size() - 1) - 1;
  azimuthFraction = std::clamp((phi - a[azimuthCell]) / (a[azimuthCell + 1] - a[azimuthCell]), 0.0, 1.0);
  polarFraction = std::clamp((theta - p[polarCell]) / (p[polarCell + 1] - p[polarCell]), 0.0, 1.0);
  return true;
}

double PhotometricDistribution::candela(const Vec3 &local) const {
  size_t i, j;
  double s, t;
  if (!locate(local, i, j, s, t)) return 0;
  const size_t np = polarRadians_.size();
  const double *c0 = &candela_[i * np + j], *c1 = &candela_[(i + 1) * np + j];
  return (1 - s) * ((1 - t) * c0[0] + t * c0[1]) + s * ((1 - t) * c1[0] + t * c1[1]);
}

double PhotometricDistribution::tiltFactor(double degrees) const {
  if (tiltDegrees_.empty() || !std::isfinite(degrees)) return 1;
  if (degrees <= tiltDegrees_.front()) return tiltFactors_.front();
  if (degrees >= tiltDegrees_.back()) return tiltFactors_.back();
  size_t k = std::upper_bound(tiltDegrees_.begin(), tiltDegrees_.end(), degrees) - tiltDegrees_.begin();
  double t = (degrees - tiltDegrees_[k - 1]) / (tiltDegrees_[k] - tiltDegrees_[k - 1]);
  return (1 - t) * tiltFactors_[k - 1] + t * tiltFactors_[k];
}

Vec3 PhotometricDistribution::sample(double u1, double u2, double &pdf) const {
  if (sampleCdf_.empty() || !(sampleCdf_.back() > 0)) {
    pdf = 0;
    return {0, 0, 1};
  }
  u1 = std::clamp(u1, 0.0, 1.0);
  size_t cell = std::min<size_t>(std::upper_bound(sampleCdf_.begin(), sampleCdf_.end(), u1) - sampleCdf_.begin(),
                                 sampleCdf_.size() - 1);
  double low = cell > 0 ? sampleCdf_[cell - 1] : 0.0;
  double u = std::clamp((u1 - low) / (sampleCdf_[cell] - low), 0.0, 1.0);
  const size_t np = polarRadians_.size();
  size_t i = cell / (np - 1), j = cell % (np - 1);
  double phi = azimuthRadians_[i] + u * (azimuthRadians_[i + 1] - azimuthRadians_[i]);
  double cos0 = std::cos(polarRadians_[j]), cos1 = std::cos(polarRadians_[j + 1]);
  pdf = samplePdf_[cell];
  return directionOf(type_, phi, cos0 + std::clamp(u2, 0.0, 1.0) * (cos1 - cos0));
}

double PhotometricDistribution::pdf(const Vec3 &local) const {
  size_t i, j;
  double s, t;
  if (samplePdf_.empty() || !locate(local, i, j, s, t)) return 0;
  return samplePdf_[i * (polarRadians_.size() - 1) + j];
}

namespace photometry_detail {

std::string readBoundedFile(const std::string &path, const std::string &format, const InputLocation &from) {
  const InputLocation at = from.file.empty() ? InputLocation{path, 0, 0, ""} : from;
  std::string text = readInputFile(path, at, format + " file", kMaxPhotometricFileBytes);
  if (text.starts_with("\xEF\xBB\xBF")) text.erase(0, 3);  // a UTF-8 byte-order mark
  return text;
}

std::string quoted(std::string_view text) {
  std::string out = "'";
  for (size_t i = 0; i < text.size() && i < 24; ++i) {
    unsigned char c = static_cast<unsigned char>(text[i]);
    out += (c >= 32 && c < 127) ? static_cast<char>(c) : '?';
  }
  if (text.size() > 24) out += "...";
  return out + "'";
}

std::string_view trim(std::string_view text) {
  auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; };
  while (!text.empty() && space(text.front())) text.remove_prefix(1);
  while (!text.empty() && space(text.back())) text.remove_suffix(1);
  return text;
}

TextCursor::TextCursor(std::string file, std::string_view text) : file_(std::move(file)), text_(text) {}

bool TextCursor::nextLine(std::string_view &line) {
  inLine_ = false;
  if (next_ >= text_.size()) return false;
  size_t end = text_.find_first_of("\r\n", next_);
  if (end == std::string_view::npos) end = text_.size();
  line = text_.substr(next_, end - next_);
  next_ = end;
  if (next_ < text_.size() && text_[next_] == '\r') ++next_;
  if (next_ < text_.size() && text_[next_] == '\n') ++next_;
  ++line_;
  return true;
}

bool TextCursor::nextToken(std::string_view &token) {
  auto separator = [](char c) {
    return c == ' ' || c == '\t' || c == ',' || c == '\f' || c == '\v' || c == '\x1a';  // \x1a: DOS end of file
  };
  for (;;) {
    if (inLine_) {
      while (!rest_.empty() && separator(rest_.front())) rest_.remove_prefix(1);
      if (!rest_.empty()) {
        size_t end = 0;
        while (end < rest_.size() && !separator(rest_[end])) ++end;
        token = rest_.substr(0, end);
        rest_.remove_prefix(end);
        return true;
      }
    }
    std::string_view line;
    if (!nextLine(line)) return false;
    rest_ = line;
    inLine_ = true;
  }
}

TextCursor::Read TextCursor::decimal(double &value, std::string_view &token) {
  if (!nextToken(token)) return Read::End;
  return parseDecimal(token, value) ? Read::Ok : Read::Bad;
}

double TextCursor::decimal(const std::string &what) {
  std::string_view token;
  double value;
  Read read = decimal(value, token);
  if (read == Read::End) throw InputError(here(), "the file ends where " + what + " (a number) was expected");
  if (read == Read::Bad) throw InputError(here(), "expected " + what + " (a number), found " + quoted(token));
  return value;
}

int64_t TextCursor::integer(const std::string &what) {
  std::string_view token;
  if (!nextToken(token)) throw InputError(here(), "the file ends where " + what + " (an integer) was expected");
  int64_t value;
  if (!parseInteger(token, value)) {
    // "37.0" for a count: an integer written as a decimal, which some writers do.
    double decimal;
    if (parseDecimal(token, decimal) && decimal == std::floor(decimal) && std::abs(decimal) < 1e15)
      return static_cast<int64_t>(decimal);
    throw InputError(here(), "expected " + what + " (an integer), found " + quoted(token));
  }
  return value;
}

std::vector<double> readAngles(TextCursor &in, int64_t count, const std::string &name, double low, double high,
                               InputLocation &firstAt) {
  std::vector<double> angles;
  angles.reserve(static_cast<size_t>(count));
  for (int64_t k = 0; k < count; ++k) {
    double angle;
    std::string_view token;
    TextCursor::Read read = in.decimal(angle, token);
    std::string which = name + " " + std::to_string(k + 1) + " of " + std::to_string(count);
    if (read == TextCursor::Read::End)
      throw InputError(in.here(), "the file ends where " + which + " was expected (is the file truncated?)");
    if (read == TextCursor::Read::Bad)
      throw InputError(in.here(), "expected " + which + " (a number of degrees), found " + quoted(token));
    if (k == 0) firstAt = in.here();
    if (angle < low || angle > high)
      throw InputError(in.here(), which + " is " + degreesText(angle) + ": expected an angle from " + degreesText(low) +
                                      " to " + degreesText(high) + " degrees");
    if (k > 0 && !(angle > angles.back()))
      throw InputError(in.here(), which + " is " + degreesText(angle) + ", not greater than the one before (" +
                                      degreesText(angles.back()) + "): expected increasing angles");
    angles.push_back(angle);
  }
  return angles;
}

/// Bounds every intensity (cd) so that sums over a whole table stay finite;
/// the brightest searchlights reach 1e9 cd.
constexpr double kMaxIntensity = 1e18, kMinIntensity = 1e-30;

void readIntensities(TextCursor &in, int64_t count, double scale, const std::string &name, std::vector<double> &out) {
  for (int64_t k = 0; k < count; ++k) {
    double value;
    std::string_view token;
    TextCursor::Read read = in.decimal(value, token);
    if (read != TextCursor::Read::Ok || value < 0 || !(value * scale <= kMaxIntensity)) {
      std::string which = name + " " + std::to_string(k + 1) + " of " + std::to_string(count);
      if (read == TextCursor::Read::End)
        throw InputError(in.here(), "the file ends where " + which + " was expected (is the file truncated?)");
      if (read == TextCursor::Read::Bad)
        throw InputError(in.here(), "expected " + which + " (a number), found " + quoted(token));
      if (value < 0) throw InputError(in.here(), which + " is negative: expected an intensity of 0 or more");
      throw InputError(in.here(), which +
                                      " times the file's multipliers is more than 1e18: expected a luminous "
                                      "intensity a luminaire can have");
    }
    // Below 1e-30 cd an intensity is no light, and a density proportional to
    // it could underflow to 0 beside 1e18 cd elsewhere (pdf must be > 0 where candela is).
    out.push_back(value * scale >= kMinIntensity ? value * scale : 0.0);
  }
}

void TextCursor::expectEnd(const std::string &after) {
  std::string_view token;
  if (nextToken(token))
    throw InputError(here(), "expected the end of the file after " + after + ", found " + quoted(token) +
                                 " (do the counts in the file match its values?)");
}

}  // namespace photometry_detail

PhotometricFormat photometricFormatOf(std::string_view text) {
  std::vector<std::string_view> lines;
  for (size_t start = 0; start < text.size() && lines.size() < 4096;) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.front()))) line.remove_prefix(1);
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.remove_suffix(1);
    lines.push_back(line);
    start = end + 1;
  }
  auto startsWith = [](std::string_view line, std::string_view prefix) {
    if (line.size() < prefix.size()) return false;
    for (size_t i = 0; i < prefix.size(); ++i)
      if (std::toupper(static_cast<unsigned char>(line[i])) != prefix[i]) return false;
    return true;
  };
  if (!lines.empty() && startsWith(lines[0], "IESNA")) return PhotometricFormat::Ies;
  for (std::string_view line : lines)
    if (startsWith(line, "TILT")) return PhotometricFormat::Ies;
  if (lines.size() < 7) return PhotometricFormat::Unknown;
  auto integerIn = [&](size_t line, int64_t low, int64_t high) {
    int64_t value = 0;
    return parseInteger(lines[line], value) && value >= low && value <= high;
  };
  // Line 5, the distance between C planes, is a decimal (some files write a decimal comma).
  if (integerIn(1, 0, 3) && integerIn(2, 0, 4) && integerIn(3, 0, 1 << 20) && !lines[4].empty() &&
      integerIn(5, 0, 1 << 20))
    return PhotometricFormat::Eulumdat;
  return PhotometricFormat::Unknown;
}

PhotometricFormat photometricFormatOfFile(const std::string &path) {
  return photometricFormatOf(readInputFilePrefix(path, 1 << 16));
}

std::shared_ptr<const PhotometricDistribution> readPhotometricFile(const std::string &path) {
  std::string extension = lowercaseExtension(path);
  if (extension == ".ies") return readIesFile(path);
  if (extension == ".ldt") return readEulumdatFile(path);
  throw InputError({path, 0, 0, ""}, "unknown photometric file extension '" + extension +
                                         "': expected .ies (IES LM-63) or .ldt (EULUMDAT)");
}

}  // namespace radiant
