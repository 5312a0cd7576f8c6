// Caustics by light-ray tracing (Chen, Rushmeier, Miller & Turner 1991,
// "caustics reconstruction"; the caustic photon map of Jensen 1996).
//
// Light that reaches a diffuse surface after one or more ideal specular
// bounces (Heckbert's L S+ D) cannot be found from the eye by sampling the
// emitters: the mirror or glass between hides them from shadow rays. Photons
// are traced from the emitters through mirrors and glass and stored where they
// first land on a non-specular surface after at least one specular bounce; the
// reflected radiance at a point is then a density estimate over a disc of
// radius r (biased, consistent as r shrinks with more photons). Every
// estimator that adds it must leave out the same paths from the eye: emission
// reached from a non-specular vertex through ≥ 1 specular bounces.
#pragma once

#include <cstdint>
#include <vector>

#include "raytrace/ray_tracer.h"

namespace radiant {

struct CausticPhoton {
  Vec3 position;
  Vec3 normal;  ///< geometric normal of the surface it landed on, on the side it arrived from
  Bands power;  ///< W
};

class CausticPhotonMap {
 public:
  /// Traces `emitted` photons from the scene's emitters (power-proportional,
  /// cosine-distributed: each carries Φ/emitted), deterministically for the
  /// seed whatever the thread count. `radius` (metres) of the density
  /// estimate; ≤ 0 chooses 1 % of the scene's bounding-box diagonal.
  /// `throughDiffuse`: photons also bounce off non-specular surfaces (by
  /// their BSDF, Russian roulette on what they absorb) and are stored at
  /// every non-specular hit that follows a specular bounce: all the light
  /// whose last bounce was specular (L (D|S)* S D), for multipass's reading
  /// of the solution, which has mirrors and glass black (render/multipass.h).
  CausticPhotonMap(const RayTracer &tracer, size_t emitted, uint64_t seed, double radius = 0,
                   bool throughDiffuse = false);

  /// Radiance reflected towards any direction by a Lambertian point of
  /// reflectance ρ: ρ/π × the caustic irradiance, Σ power / (π r²) over the
  /// photons within r that arrived on the same side of a surface facing the same way.
  Bands reflectedRadiance(const Vec3 &position, const Vec3 &normal, const Bands &rho) const;
  /// The caustic irradiance itself, W·m⁻².
  Bands irradiance(const Vec3 &position, const Vec3 &normal) const;

  size_t emitted() const { return emitted_; }
  size_t stored() const { return photons_.size(); }
  double radius() const { return radius_; }
  const std::vector<CausticPhoton> &photons() const { return photons_; }

 private:
  /// The grid cell of side 2r holding a point (one integer per axis).
  void cellOf(const Vec3 &p, int64_t cell[3]) const;
  static uint64_t cellKey(int64_t x, int64_t y, int64_t z);
  /// The photons listed in one cell: [first, last) in order_, or an empty range.
  std::pair<uint32_t, uint32_t> cellRange(uint64_t key) const;
  void buildGrid();

  std::vector<CausticPhoton> photons_;
  /// A lookup happens at every non-specular vertex of every path, and almost
  /// every one lands where no caustic is: it must cost a few cache reads.
  /// Cells of side 2r, each listing the photons within r of it (a photon in
  /// 8 cells); an occupancy bitset answers "no photons here" before the hash
  /// table is touched.
  struct Slot {
    uint64_t key = kEmptyKey;
    uint32_t first = 0, last = 0;
  };
  static constexpr uint64_t kEmptyKey = ~uint64_t(0);
  /// A photon as a lookup reads it, copied into every cell it is listed in,
  /// contiguous since a lookup scans a whole cell (normal and power in single precision).
  struct GridPhoton {
    Vec3 position;
    float normal[3], power[kBandCount];
  };
  std::vector<GridPhoton> cellPhotons_;  ///< by cell
  std::vector<Slot> table_;              ///< open addressing, linear probing, power-of-two size
  std::vector<uint64_t> occupied_;       ///< one bit per hashed cell key
  size_t emitted_ = 0;
  double radius_ = 0, cellSize_ = 0;
};

}  // namespace radiant
