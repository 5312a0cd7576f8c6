#include "radiosity/direct_light_mesh.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "radiosity/backprojection.h"
#include "radiosity/direct_refinement.h"
#include "util/phase.h"

namespace radiant {

DirectLightMesh buildDirectLightMesh(const Scene &scene, const RayTracer &tracer, const MeshOptions &meshOptions,
                                     const SolverOptions &options) {
  // The trees only: the refinement below builds the elements once, at its end.
  DirectLightMesh result{buildTreeMesh(scene, meshOptions, /*buildElements=*/false), {}, {}};
  RadiosityMesh &mesh = result.mesh;
  // The refinement's weight (ρ, or τ) on the patches of at least four
  // elements' area, none on the others: a model's facets, and the long
  // slivers of a CAD model's cylinders, which the element size divides
  // along their length only.
  double element = 0;
  for (const MeshTreeNode &t : mesh.tree)
    if (t.isLeaf()) element = std::max(element, t.longestEdge());
  std::vector<Bands> weights = directRefinementWeights(scene, mesh);
  bool anyLarge = false;
  for (uint32_t p = 0; p < mesh.patches.size(); ++p) {
    if (mesh.patches[p].area >= 4 * element * element)
      anyLarge = anyLarge || weights[p].max() > 0;
    else
      weights[p] = Bands(0.0);
  }
  // As hierarchical-exact: exact up to 48 faces in a point's shaft to a light, a grid of shadow rays beyond.
  constexpr size_t kMaxExactOccluders = 48;
  const DirectIrradiance direct(scene, tracer, kMaxExactOccluders);
  if (!anyLarge || direct.empty()) {
    rebuildElementsFromTrees(mesh);
    return result;
  }
  DirectLightField field(scene, direct);
  Box3 bounds;
  for (const Vec3 &p : scene.positions) bounds.extend(p);
  const double extent =
      std::max({bounds.hi.x - bounds.lo.x, bounds.hi.y - bounds.lo.y, bounds.hi.z - bounds.lo.z, 1e-9});
  DirectRefinementOptions refinement;
  refinement.minimumEdge = options.directMinimumEdge > 0 ? options.directMinimumEdge : extent / 256;
  field.setSmallestSplit(refinement.minimumEdge);
  refinement.maxElements = options.maxElements;
  refinement.threads = options.threads;
  refinement.tolerance =
      options.directTolerance * meanFirstBounce(mesh, field, weights, options.threads, /*weightedOnly=*/true);
  const Phase phase("refining the mesh to the direct light");
  const size_t split = refineForDirectLight(mesh, weights, field, refinement);
  if (std::getenv("RADIANT_TIMING"))
    std::fprintf(stderr, "  direct-light mesh: %zu leaves split, %zu elements, %zu points evaluated\n", split,
                 mesh.elements.size(), field.size());
  // What the solver need not evaluate again: the refined patches' nodes
  // (evaluated as directLightOfMesh would, a hair inside the patch, with
  // its normal) and their leaves' means.
  const Bands unknown(std::numeric_limits<double>::quiet_NaN());
  result.nodeDirect.assign(mesh.nodes.size(), unknown);
  result.elementDirect.assign(mesh.elements.size(), unknown);
  for (uint32_t v = 0; v < mesh.nodes.size(); ++v)
    if (weights[mesh.nodePatch[v]].max() > 0 && field.has(mesh.nodePatch[v], mesh.nodes[v]))
      result.nodeDirect[v] = field.at(mesh.nodePatch[v], mesh.nodes[v]);
  for (const MeshTreeNode &t : mesh.tree)
    if (t.isLeaf() && t.element >= 0 && weights[t.patch].max() > 0)
      result.elementDirect[t.element] = field.nodeAverage(t);
  return result;
}

}  // namespace radiant
