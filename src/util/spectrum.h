// Radiometric values per band.
//
// The band count is one definition (kBandCount) so spectral scenes can later run
// the same code per wavelength sample (Cohen & Wallace §9.5). Today the bands are
// linear Rec.709/sRGB primaries R, G, B.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace radiant {

constexpr int kBandCount = 3;

/// A value per band: radiance in W·sr⁻¹·m⁻², radiosity in W·m⁻², or a
/// dimensionless reflectance, depending on where it is used.
struct Bands {
  std::array<double, kBandCount> v{};

  constexpr Bands() = default;
  constexpr explicit Bands(double s) { v.fill(s); }
  constexpr Bands(double r, double g, double b) : v{r, g, b} {}

  constexpr double operator[](int i) const { return v[i]; }
  constexpr double &operator[](int i) { return v[i]; }

  Bands &operator+=(const Bands &o) {
    for (int i = 0; i < kBandCount; ++i) v[i] += o.v[i];
    return *this;
  }
  Bands &operator*=(const Bands &o) {
    for (int i = 0; i < kBandCount; ++i) v[i] *= o.v[i];
    return *this;
  }
  Bands &operator*=(double s) {
    for (auto &x : v) x *= s;
    return *this;
  }

  double max() const { return *std::max_element(v.begin(), v.end()); }
  double min() const { return *std::min_element(v.begin(), v.end()); }
  double average() const {
    double s = 0;
    for (double x : v) s += x;
    return s / kBandCount;
  }
  bool isBlack() const { return max() <= 0.0 && min() >= 0.0; }
  bool isFinite() const {
    for (double x : v)
      if (!std::isfinite(x)) return false;
    return true;
  }
  /// Luminance weights of linear Rec.709 primaries (Y row of the sRGB→XYZ matrix).
  double luminance() const { return 0.2126390 * v[0] + 0.7151687 * v[1] + 0.0721923 * v[2]; }
};

inline Bands operator+(Bands a, const Bands &b) {
  return a += b;
}
inline Bands operator-(Bands a, const Bands &b) {
  for (int i = 0; i < kBandCount; ++i) a[i] -= b[i];
  return a;
}
inline Bands operator*(Bands a, const Bands &b) {
  return a *= b;
}
inline Bands operator*(Bands a, double s) {
  return a *= s;
}
inline Bands operator*(double s, Bands a) {
  return a *= s;
}
inline Bands operator/(Bands a, double s) {
  return a *= 1.0 / s;
}

/// Luminous efficacy of the maximum of V(λ), lm/W: turns luminance-weighted
/// radiance into cd/m².
constexpr double kLuminousEfficacy = 683.0;

}  // namespace radiant
