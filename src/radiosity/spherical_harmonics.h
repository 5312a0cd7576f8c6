// Directional light of a cluster as real spherical harmonics up to l = 2
// (9 coefficients), after Ramamoorthi & Hanrahan, "An efficient
// representation for irradiance environment maps", SIGGRAPH 2001.
//
// A cluster of many small surfaces (a tessellated model) sends and receives
// light in a way that depends on direction: its radiant intensity toward ω is
// I(ω) = Σ_i (R_i A_i / π) max(0, n_i·ω), a sum of clamped-cosine lobes, and
// a surface inside it with normal n receives E(n) = ∫ L(ω) max(0, n·ω) dω
// from the radiance L arriving at it. Both are convolutions with the clamped
// cosine, whose spherical-harmonic coefficients fall off fast: Â_0 = π,
// Â_1 = 2π/3, Â_2 = π/4, then 0 for odd l > 1 and under 0.05·π beyond. Nine
// coefficients hold either function to within about 9 % of its peak (the
// largest miss, for a single lobe, is at grazing and behind it: the L2
// approximation of max(0, cos θ) is 1/4 + cos θ/2 + 5/16·(3cos²θ − 1)/2,
// 1.0625 at θ = 0, 0.094 at 90°, 0.0625 at 180°), and exactly the average
// over directions. The refinement oracle charges a link through a large
// cluster for that (reflected_light_hierarchy.h); small clusters are summed
// patch by patch instead.
#pragma once

#include <array>

#include "util/math.h"
#include "util/spectrum.h"

namespace radiant {

constexpr int kHarmonics = 9;

/// Real spherical harmonics Y_0 … Y_8 (l ≤ 2) at a unit direction.
inline std::array<double, kHarmonics> harmonicsAt(const Vec3 &d) {
  return {0.282094791773878,
          0.488602511902920 * d.y,
          0.488602511902920 * d.z,
          0.488602511902920 * d.x,
          1.092548430592079 * d.x * d.y,
          1.092548430592079 * d.y * d.z,
          0.315391565252520 * (3 * d.z * d.z - 1),
          1.092548430592079 * d.x * d.z,
          0.546274215296040 * (d.x * d.x - d.y * d.y)};
}

/// The clamped cosine's convolution factors Â_l for coefficient k (band l).
inline double clampedCosineFactor(int k) {
  return k == 0 ? kPi : (k < 4 ? 2 * kPi / 3 : kPi / 4);
}

/// A function on the sphere per band, as 9 coefficients.
struct HarmonicBands {
  std::array<Bands, kHarmonics> c{};

  HarmonicBands &operator+=(const HarmonicBands &o) {
    for (int k = 0; k < kHarmonics; ++k) c[k] += o.c[k];
    return *this;
  }
  /// Adds w·max(0, n·ω), a clamped-cosine lobe about unit n of weight w.
  void addLobe(const Vec3 &n, const Bands &w) {
    const auto y = harmonicsAt(n);
    for (int k = 0; k < kHarmonics; ++k) c[k] += w * (clampedCosineFactor(k) * y[k]);
  }
  /// Adds a delta of weight w in unit direction d (light arriving from d).
  void addDelta(const Vec3 &d, const Bands &w) {
    const auto y = harmonicsAt(d);
    for (int k = 0; k < kHarmonics; ++k) c[k] += w * y[k];
  }
  /// Adds radiance arriving alike from every direction, so that a surface of
  /// any orientation takes irradiance e from it.
  void addIsotropic(const Bands &e) { c[0] += e * (1 / (kPi * 0.282094791773878)); }
  /// The function's value at unit direction d, clamped at 0.
  Bands value(const Vec3 &d) const {
    const auto y = harmonicsAt(d);
    Bands v(0.0);
    for (int k = 0; k < kHarmonics; ++k) v += c[k] * y[k];
    for (int b = 0; b < kBandCount; ++b) v[b] = std::max(0.0, v[b]);
    return v;
  }
  /// The irradiance a surface of unit normal n receives from this function
  /// taken as incident radiance, clamped at 0: Σ Â_l c_k Y_k(n).
  Bands irradiance(const Vec3 &n) const {
    const auto y = harmonicsAt(n);
    Bands v(0.0);
    for (int k = 0; k < kHarmonics; ++k) v += c[k] * (clampedCosineFactor(k) * y[k]);
    for (int b = 0; b < kBandCount; ++b) v[b] = std::max(0.0, v[b]);
    return v;
  }
};

}  // namespace radiant
