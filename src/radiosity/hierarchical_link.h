// The form factor of one link of the classic hierarchical solver
// (`hierarchical`, hierarchical.cpp; Hanrahan, Salzman & Aupperle 1991):
// the receiver's grid of points against stratified points of the source,
// with the shadow rays between them.
#pragma once

#include <array>
#include <cstdint>

#include "raytrace/ray_tracer.h"
#include "util/math.h"
#include "util/random.h"

namespace radiant {

/// A quadtree node's shape: a triangle or a quad (corners counter-clockwise about `normal`).
struct HierarchicalLinkEnd {
  int vertexCount = 4;
  std::array<Vec3, 4> corners{};
  Vec3 centre, normal;
  double area = 0;
};

/// What measuring a link finds. Trivially copyable, 24 bytes: MPI ranks share it as its bytes.
struct LinkMeasure {
  double formFactor = 0;            ///< F(receiver ← source), occlusion included
  double unoccludedFormFactor = 0;  ///< F as if nothing were in between
  uint32_t shadowRays = 0;          ///< traced
  uint32_t arrived = 0;             ///< of them, those that reached the source
  /// The fraction of the shadow rays that arrived: none, partial or full visibility.
  double visibleFraction() const { return shadowRays ? double(arrived) / shadowRays : 1.0; }
};

/// F(p ← q) = F_unoccluded × V. F_unoccluded is the point-to-polygon factor
/// (Lambert's contour integral) averaged over an m × m grid of receiver
/// points, m = max(4, √visibilitySamples): deterministic, so links between
/// neighbours that share an edge, where F(x → q) has a log singularity, stay
/// accurate. V is the visibility of pairs (grid point, random source point),
/// each pair weighted by the kernel cosθ_p cosθ_q /(π r² + a) it stands for.
/// `rng` is the link's own generator: the measure does not depend on which
/// thread or rank takes it.
LinkMeasure measureHierarchicalLink(const RayTracer &tracer, const HierarchicalLinkEnd &receiver,
                                    const HierarchicalLinkEnd &source, int visibilitySamples, Pcg32 rng);

}  // namespace radiant
