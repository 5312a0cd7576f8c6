// Spectra → CIE XYZ → linear sRGB (CIE 1931 2° observer; IEC 61966-2-1;
// Cohen & Wallace §9.5).
//
// The CIE table itself is in cie1931.cpp. Everything here is double precision;
// the sRGB matrices are derived from the primaries and the white, not typed in,
// so the two directions are inverses to rounding and D65 maps to (1, 1, 1);
// they reproduce the 7-decimal matrices of docs/spectral.md, Colour
// (tests/colour_test.cpp).
#include "colour/spectrum.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace radiant {

namespace {

Matrix3 transpose(const Matrix3 &m) {
  return {Vec3{m[0].x, m[1].x, m[2].x}, Vec3{m[0].y, m[1].y, m[2].y}, Vec3{m[0].z, m[1].z, m[2].z}};
}

/// Inverse by cofactors: the columns of m⁻¹ are the cross products of m's rows over det m.
Matrix3 inverse(const Matrix3 &m) {
  const Vec3 c0 = cross(m[1], m[2]), c1 = cross(m[2], m[0]), c2 = cross(m[0], m[1]);
  const double det = dot(m[0], c0);
  return transpose({c0 / det, c1 / det, c2 / det});
}

Matrix3 diagonal(const Vec3 &d) {
  return {Vec3{d.x, 0, 0}, Vec3{0, d.y, 0}, Vec3{0, 0, d.z}};
}

/// XYZ with Y = 1 of a chromaticity (x, y).
Vec3 xyzOfChromaticity(double x, double y) {
  return {x / y, 1.0, (1.0 - x - y) / y};
}

/// Linear sRGB → XYZ, derived from the Rec.709 primaries and the D65 white
/// (IEC 61966-2-1): the primaries' XYZ are the columns,
/// each scaled so that RGB (1, 1, 1) is the white.
Matrix3 deriveSrgbToXyz() {
  const Matrix3 primaries =
      transpose({xyzOfChromaticity(0.64, 0.33), xyzOfChromaticity(0.30, 0.60), xyzOfChromaticity(0.15, 0.06)});
  const Vec3 scale = inverse(primaries) * kD65White;
  return primaries * diagonal(scale);
}

const Matrix3 &srgbToXyzMatrix() {
  static const Matrix3 matrix = deriveSrgbToXyz();
  return matrix;
}

const Matrix3 &xyzToSrgbMatrix() {
  static const Matrix3 matrix = inverse(srgbToXyzMatrix());
  return matrix;
}

/// XYZ → Bradford "cone" responses (Lam 1985; the linearised form used by
/// ICC v4 and CIECAM97s).
constexpr Matrix3 kBradfordConeResponse{Vec3{0.8951, 0.2664, -0.1614}, Vec3{-0.7502, 1.7135, 0.0367},
                                        Vec3{0.0389, -0.0685, 1.0296}};

void requireValidBands(const std::vector<double> &wavelengths) {
  if (wavelengths.size() < 2)
    throw std::invalid_argument(
        fmt::format("colour matching needs at least 2 band wavelengths, got {}", wavelengths.size()));
  for (size_t i = 0; i < wavelengths.size(); ++i) {
    const double nm = wavelengths[i];
    if (!(nm >= kCieFirstWavelength && nm <= kCieLastWavelength))
      throw std::invalid_argument(fmt::format("band wavelength {} nm lies outside the CIE table ({}–{} nm)", nm,
                                              kCieFirstWavelength, kCieLastWavelength));
    if (i > 0 && !(nm > wavelengths[i - 1]))
      throw std::invalid_argument(
          fmt::format("band wavelengths must increase strictly: {} nm follows {} nm", nm, wavelengths[i - 1]));
  }
  // Σȳ over the integer wavelengths normalises the weights; without one it is zero.
  if (std::ceil(wavelengths.front()) > std::floor(wavelengths.back()))
    throw std::invalid_argument("band wavelengths must span at least one integer nm");
}

}  // namespace

double SampledSpectrum::at(double wavelengthNm) const {
  if (values.empty()) return 0.0;
  if (wavelengthNm <= wavelengths.front()) return values.front();
  if (wavelengthNm >= wavelengths.back()) return values.back();
  // First sample strictly above λ; λ lies in [wavelengths[i-1], wavelengths[i]).
  const size_t i = size_t(std::upper_bound(wavelengths.begin(), wavelengths.end(), wavelengthNm) - wavelengths.begin());
  const double t = (wavelengthNm - wavelengths[i - 1]) / (wavelengths[i] - wavelengths[i - 1]);
  return (1.0 - t) * values[i - 1] + t * values[i];
}

double cieYIntegral(int first, int last) {
  double sum = 0.0;
  for (int nm = std::max(first, kCieFirstWavelength); nm <= std::min(last, kCieLastWavelength); ++nm)
    sum += cieColourMatching(nm).y;
  return sum;
}

Vec3 spectrumToXyz(const SampledSpectrum &spectrum, int first, int last) {
  const double yIntegral = cieYIntegral(first, last);
  if (!(yIntegral > 0))
    throw std::invalid_argument(fmt::format("spectrumToXyz: [{}, {}] nm holds no CIE table wavelength", first, last));
  Vec3 sum;
  for (int nm = std::max(first, kCieFirstWavelength); nm <= std::min(last, kCieLastWavelength); ++nm)
    sum += spectrum.at(nm) * cieColourMatching(nm);
  return sum / yIntegral;
}

Vec3 xyzToLinearSrgb(const Vec3 &xyz) {
  return xyzToSrgbMatrix() * xyz;
}

Vec3 linearSrgbToXyz(const Vec3 &rgb) {
  return srgbToXyzMatrix() * rgb;
}

std::array<double, 2> chromaticity(const Vec3 &xyz) {
  const double sum = xyz.x + xyz.y + xyz.z;
  if (sum == 0.0) return {0.0, 0.0};
  return {xyz.x / sum, xyz.y / sum};
}

Matrix3 operator*(const Matrix3 &a, const Matrix3 &b) {
  const Matrix3 columns = transpose(b);
  Matrix3 product;
  for (int r = 0; r < 3; ++r) product[r] = {dot(a[r], columns[0]), dot(a[r], columns[1]), dot(a[r], columns[2])};
  return product;
}

Matrix3 bradfordAdaptation(const Vec3 &sourceWhite, const Vec3 &destinationWhite) {
  // von Kries: scale each cone response by destination / source white, in the Bradford cone space.
  const Vec3 source = kBradfordConeResponse * sourceWhite, destination = kBradfordConeResponse * destinationWhite;
  const Vec3 gain{destination.x / source.x, destination.y / source.y, destination.z / source.z};
  return inverse(kBradfordConeResponse) * diagonal(gain) * kBradfordConeResponse;
}

BandColourMatching::BandColourMatching(std::vector<double> wavelengths) : wavelengths_(std::move(wavelengths)) {
  requireValidBands(wavelengths_);
  // Each integer λ in the bands' range lies in one segment [w_k, w_k+1]; the two
  // tents that are non-zero there take (1 − t) and t of its (x̄, ȳ, z̄).
  xyzWeights_.assign(wavelengths_.size(), Vec3{});
  const int first = int(std::ceil(wavelengths_.front())), last = int(std::floor(wavelengths_.back()));
  size_t k = 0;
  for (int nm = first; nm <= last; ++nm) {
    while (k + 2 < wavelengths_.size() && nm > wavelengths_[k + 1]) ++k;
    const double t = (nm - wavelengths_[k]) / (wavelengths_[k + 1] - wavelengths_[k]);
    const Vec3 cmf = cieColourMatching(nm);
    xyzWeights_[k] += (1.0 - t) * cmf;
    xyzWeights_[k + 1] += t * cmf;
  }
  const double yIntegral = cieYIntegral(first, last);
  for (Vec3 &w : xyzWeights_) w = w / yIntegral;
}

Vec3 BandColourMatching::toXyz(std::span<const double> values) const {
  if (values.size() != wavelengths_.size())
    throw std::invalid_argument(fmt::format("toXyz: {} values for {} bands", values.size(), wavelengths_.size()));
  Vec3 xyz;
  for (size_t i = 0; i < values.size(); ++i) xyz += values[i] * xyzWeights_[i];
  return xyz;
}

std::vector<Vec3> BandColourMatching::linearSrgbWeights(WhiteBalance balance) const {
  Matrix3 adaptation{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
  if (balance == WhiteBalance::EqualEnergy) adaptation = bradfordAdaptation(equalEnergyWhite(), kD65White);
  std::vector<Vec3> weights;
  weights.reserve(xyzWeights_.size());
  for (const Vec3 &w : xyzWeights_) weights.push_back(xyzToLinearSrgb(adaptation * w));
  return weights;
}

Vec3 BandColourMatching::equalEnergyWhite() const {
  Vec3 sum;
  for (const Vec3 &w : xyzWeights_) sum += w;
  return sum;
}

}  // namespace radiant
