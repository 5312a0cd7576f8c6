// `hierarchical-exact` — the default solver: the direct light exact at every
// mesh node, the reflected light by hierarchical radiosity.
//
// The radiosity B = E + ρ(H_direct + H_reflected) is split where the two
// parts need different tools:
//
// 1. H_direct, the light arriving straight from the emitters, carries the
//    shadows and penumbrae. It is computed exactly, point by point, by
//    backprojection (radiosity/backprojection.h), and the patch trees are
//    refined until it interpolates bilinearly within a tolerance
//    (radiosity/direct_refinement.h). Each element's mean is Simpson's rule
//    over those exact values; the display interpolates the exact values at
//    the nodes (Solution::nodeDirectIrradiance), so shadows are as sharp as
//    the mesh, and no shadow ray's noise enters them.
// 2. H_reflected, the light reflected at least once, is smooth and is
//    carried by hierarchical radiosity with clusters over the same trees
//    (radiosity/reflected_light_hierarchy.h): links between tree nodes whose
//    form factors are exact at the receiver's cubature points, as
//    polynomials over both ends, and, above the patches, links with clusters
//    of patches, so that a scene of 10⁵ triangles is not linked pair by pair.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "radiosity/backprojection.h"
#include "radiosity/direct_refinement.h"
#include "radiosity/reflected_light_hierarchy.h"
#include "radiosity/solver.h"
#include "util/phase.h"
#include "util/timing.h"

namespace radiant {

void solveHierarchicalExact(const RayTracer &tracer, Solution &s, const SolverOptions &options,
                            const SolverProgressCallback &progress) {
  const auto start = std::chrono::steady_clock::now();
  TimingLaps laps;
  const Scene &scene = tracer.scene();
  RadiosityMesh &mesh = s.mesh;
  // A uniform mesh (a caller's, not meshAndSolve's): its patches become the
  // trees' roots, and the refinement below makes the elements again.
  if (mesh.tree.empty()) {
    makePatchTrees(mesh);
    rebuildElementsFromTrees(mesh);
  }

  // 1. The direct light, exact, and the trees refined for it.
  // Exact up to kMaxExactOccluders faces in a point's shaft to a light,
  // sampled with a fixed grid of shadow rays beyond (a tessellated model in
  // the way; DirectIrradiance::sampledFormFactor).
  constexpr size_t kMaxExactOccluders = 48;
  DirectIrradiance direct(scene, tracer, kMaxExactOccluders);
  DirectLightField field(scene, direct);
  // ρ, or τ where a translucent face passes more of its direct light to its other side.
  const std::vector<Bands> patchReflectance = directRefinementWeights(scene, mesh);
  const double extent = [&] {
    Box3 b;
    for (const Vec3 &p : scene.positions) b.extend(p);
    return std::max({b.hi.x - b.lo.x, b.hi.y - b.lo.y, b.hi.z - b.lo.z, 1e-9});
  }();
  DirectRefinementOptions refinement;
  refinement.minimumEdge = options.directMinimumEdge > 0 ? options.directMinimumEdge : extent / 256;
  field.setSmallestSplit(refinement.minimumEdge);
  refinement.maxElements = options.maxElements;
  refinement.threads = options.threads;
  // Both tolerances are relative to the scene's mean first-bounce radiosity,
  // the area mean of ρ·H_direct, measured on the starting mesh.
  const double firstBounce = meanFirstBounce(mesh, field, patchReflectance, options.threads);
  refinement.tolerance = options.directTolerance * firstBounce;
  {
    const Phase phase("refining the mesh to the direct light");
    refineForDirectLight(mesh, patchReflectance, field, refinement);
  }
  laps.lap("direct light and its mesh");

  // 2. The reflected light by hierarchical radiosity on the same trees.
  const double minimumEdge = options.linkMinimumEdge > 0 ? options.linkMinimumEdge : extent / 64;
  ReflectedLightHierarchy hierarchy(scene, tracer, mesh, field, options, minimumEdge);
  hierarchy.initialiseFromDirectLight();
  hierarchy.setThreshold(options.linkError * firstBounce);
  {
    // How many links the refinement will make is known only at its end: the
    // phase says what runs and for how long, without an ETA.
    const Phase phase("linking the reflected light");
    hierarchy.link();
  }
  laps.lap("linking");
  const int maxSweeps = options.maxIterations > 0 ? options.maxIterations : 1000;
  int total = 0;
  double residual = 0;
  for (int round = 0; round < std::max(1, options.refinementRounds); ++round) {
    if (round > 0 && hierarchy.rerefine() == 0) break;
    laps.lap("re-linking");
    hierarchy.solve(options.tolerance, maxSweeps, residual, progress, total, start);
    laps.lap("solving");
  }
  s.stats.iterations = total;
  s.stats.residual = residual;
  s.stats.formFactorRays = hierarchy.rays();
  s.stats.links = hierarchy.linkCount();
  s.stats.clusterLinks = hierarchy.clusterLinkCount();
  hierarchy.writeTo(s);
  // The node irradiances were computed per patch (each node's direct light
  // with its own patch's normal, its reflected light from its own patch's
  // leaves): one value per pool of facets (Solution::poolNodeIrradiance),
  // so a smooth surface's facets meet without a seam. Averaging the facets'
  // values (rather than evaluating again with the pool's mean or shading
  // normal) costs no rays; for light from above all the facets' planes
  // irradiance is linear in the normal, so the mean is
  // the irradiance for the area-weighted mean of the facets' normals, which
  // is shorter than unit by cos(θ/2) for facets θ apart (0.2 % at 7°, 1 % at
  // 15°): the stochastic solver evaluates once with that mean's direction
  // (radiosity/node_direct_light.cpp).
  s.poolNodeIrradiance();
  laps.lap("writing the solution");
  if (timingRequested())
    std::fprintf(stderr, "  links %zu (%zu with clusters), sweeps %d\n", hierarchy.linkCount(),
                 hierarchy.clusterLinkCount(), total);
}

}  // namespace radiant
