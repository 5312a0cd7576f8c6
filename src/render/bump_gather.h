// Bump maps in interpolated radiosity display: Chen & Wu (SIGGRAPH 1990)'s
// perturbed radiosity, as C&W §9.4 describes it.
//
// A bump map tilts the shading normal far below the scale of the radiosity
// mesh, and the irradiance of a tilted surface differs from the flat one's:
// it faces the light more or less. At each node of a bump-mapped patch one
// gather of the incident radiance (rays reading the solution) is re-weighted
// for several orientations of the normal — ΔF' = ΔF·max(0, n'·ω)/(n·ω), the
// resumming of delta form factors — giving the irradiance ratio
// r(n') = H(n')/H(n) for each. At a pixel the bumped normal selects and
// interpolates among the node's orientations, and the ratios of the element's
// nodes are interpolated like B: the reflected radiosity is (B̂ − E)·r, per band.
// r(n) = 1 exactly, so a flat map changes nothing. The directions a tilted
// normal sees below the node's horizon bring nothing — Chen's "missing
// directions", and the convention of the path tracer, whose shading normals
// never let light through the geometric surface — so in a furnace
// r(θ') = (1 + cos θ')/2 and every method agrees on a bumped surface.
#pragma once

#include <vector>

#include "radiosity/solution.h"
#include "raytrace/ray_tracer.h"
#include "util/parameters.h"

namespace radiant {

struct BumpGatherOptions {
  int orientations = 16;  ///< tilted normals per node: 2 tilts (30°, 60°) × orientations/2 azimuths; even, ≥ 4
  int rays = 1024;        ///< gather rays per node, stratified over its hemisphere (32 × 32)
  uint64_t seed = 1;
  /// Gather only reflected light (B − E of what the rays meet): the ratio for
  /// shirley's and kok's interpolated indirect light, whose direct part is per pixel.
  bool reflectedOnly = false;
};

/// bump-orientations: the parameter of the methods that interpolate bumped
/// radiosity (interpolate, shirley, kok, multipass); even, 4…64.
const ParameterSpec &bumpOrientationsParameter();
/// Its value, checked to be even (an InputError at its origin).
int bumpOrientations(const Parameters &parameters);

class BumpGather {
 public:
  /// Gathers at every node of a patch whose material has a bump or normal map
  /// (none: empty, and ratio() is 1). Deterministic for the seed.
  BumpGather(const RayTracer &tracer, const Solution &solution, const BumpGatherOptions &options);

  bool empty() const { return nodeTable_.empty(); }
  /// r(n') at a location, interpolated from the element's nodes; n' is the
  /// bumped shading normal and `unbumpedNormal` the shading normal it
  /// perturbs: n' is first turned by the rotation that takes the unbumped
  /// normal to the patch's, so that smooth shading is not counted as a bump.
  Bands ratio(const MeshLocation &location, const Vec3 &bumpedNormal, const Vec3 &unbumpedNormal) const;
  /// r(n') of one node (tests).
  Bands nodeRatio(uint32_t node, const Vec3 &bumpedNormal) const;
  int tilts() const { return kTilts; }

  static constexpr int kTilts = 2;
  static constexpr double kTiltStepDegrees = 30;

 private:
  const Solution &solution_;
  int azimuths_ = 8;
  std::vector<int32_t> nodeTable_;  ///< per mesh node: index of its table in ratios_, or −1
  std::vector<float> ratios_;       ///< per gathered node: kTilts × azimuths ratios, per band
};

}  // namespace radiant
