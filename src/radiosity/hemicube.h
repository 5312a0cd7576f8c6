// The hemicube (Cohen & Greenberg 1985): form factors from a point to
// everything it sees, by projecting the scene onto the five faces of a cube
// around the normal and summing precomputed delta form factors (Cohen & Wallace
// ch. 4).
//
// Radiant traces the hemicube's pixels with Embree instead of rasterising:
// one ray per pixel through its centre, the same visibility as a z-buffer with
// no clipping code, and the same aliasing behaviour the chapter discusses.
#pragma once

#include <functional>
#include <vector>

#include "raytrace/ray_tracer.h"
#include "util/random.h"

namespace radiant {

class Hemicube {
 public:
  /// `resolution`: pixels across the full top face (rounded up to even); side
  /// faces are resolution × resolution/2.
  explicit Hemicube(int resolution);

  int resolution() const { return resolution_; }
  /// Σ of all delta form factors (≈ 1, error O(1/res²); sums in
  /// docs/radiosity.md, Form factors).
  double totalDeltaFormFactor() const;
  double topFaceDeltaFormFactor() const;
  double sideFaceDeltaFormFactor() const;  ///< one side face

  /// Casts the hemicube at `p` (normal `n`) and adds each pixel's delta form
  /// factor to `formFactors[target(hit)]`; `target` maps a hit to an index (or
  /// −1 to ignore it). With `randomRotation` the cube is turned by a random
  /// angle about n (rad.c's remedy for aliasing). Returns Σ ΔF that hit nothing.
  double gather(const RayTracer &tracer, const Vec3 &p, const Vec3 &n, const std::function<int(const Hit &)> &target,
                std::vector<double> &formFactors, Pcg32 &rng, bool randomRotation = true) const;

 private:
  struct Pixel {
    Vec3 direction;  ///< in the cube's frame, unnormalised (pixel centre)
    double deltaFormFactor;
  };
  int resolution_;
  std::vector<Pixel> pixels_;  ///< all five faces
  double top_ = 0, side_ = 0;
};

}  // namespace radiant
