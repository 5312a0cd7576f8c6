#include "radiosity/solution_query.h"

#include <algorithm>

namespace radiant {

namespace {

/// B at the point as its reconstruction takes it, ambient included.
Bands reconstructedRadiosity(const Solution &solution, const SolutionPoint &point) {
  return point.reconstruction == Reconstruction::Interpolated ? solution.interpolatedRadiosity(point.location)
                                                              : solution.displayRadiosity(point.location.element);
}

Bands clampedAtZero(Bands b) {
  for (int k = 0; k < kBandCount; ++k) b[k] = std::max(0.0, b[k]);
  return b;
}

}  // namespace

bool locateHit(const Solution &solution, const Hit &hit, const Vec3 &wo, SolutionPoint &out,
               Reconstruction reconstruction) {
  if (dot(wo, hit.geometricNormal) <= 0) return false;  // the one-sided solution says nothing of back sides
  if (solution.mesh.patchOfFace[hit.face] < 0) return false;
  out.location = solution.mesh.locate(hit.face, hit.position);
  out.reconstruction = reconstruction;
  out.reflectedScale = Bands(1.0);
  out.scaled = false;
  return true;
}

Bands textureFactor(const Solution &solution, const MeshLocation &location, const Bands &rho,
                    Reconstruction reconstruction) {
  const bool interpolated = reconstruction == Reconstruction::Interpolated && !solution.nodeReflectance.empty();
  const Bands average =
      interpolated ? solution.interpolate(solution.nodeReflectance, location) : solution.reflectance[location.element];
  Bands factor(0.0);
  for (int b = 0; b < kBandCount; ++b)
    factor[b] = average[b] > 0 ? rho[b] / average[b] : 0.0;  // ρ̄ = 0: nothing reflected
  return factor;
}

void applySurfaceDetail(const Solution &solution, const Material &material, const Bands &rho, SolutionPoint &point) {
  point.scaled = material.hasSurfaceDetail();
  point.reflectedScale = material.diffuseTextureIndex >= 0
                             ? textureFactor(solution, point.location, rho, point.reconstruction)
                             : Bands(1.0);
}

Bands reflectedRadiosity(const Solution &solution, const SolutionPoint &point) {
  Bands reflected = reconstructedRadiosity(solution, point) - solution.emission[point.location.element];
  if (point.scaled) reflected *= point.reflectedScale;
  return clampedAtZero(reflected);
}

Bands radiosity(const Solution &solution, const SolutionPoint &point) {
  const Bands &emission = solution.emission[point.location.element];
  if (point.scaled) return emission + reflectedRadiosity(solution, point);
  // max(B, E) is E + max(0, B − E) without its round-off: an unscaled reading is B itself.
  Bands b = reconstructedRadiosity(solution, point);
  for (int k = 0; k < kBandCount; ++k) b[k] = std::max(b[k], emission[k]);
  return b;
}

Bands reflectedRadiosity(const Solution &solution, uint32_t element) {
  return clampedAtZero(solution.displayRadiosity(element) - solution.emission[element]);
}

std::vector<Bands> nodeField(const Solution &solution, Field field) {
  return field == Field::Direct ? solution.nodeDirectRadiosity() : solution.nodeIndirectRadiosity();
}

Bands fieldRadiance(const Solution &solution, const std::vector<Bands> &nodeValues, const SolutionPoint &point) {
  Bands radiance = solution.interpolate(nodeValues, point.location) * kInvPi;
  if (point.scaled) radiance *= point.reflectedScale;
  return clampedAtZero(radiance);
}

double errorEstimate(const Solution &solution, const SolutionPoint &point) {
  return solution.errorEstimate[point.location.element];
}

bool isHierarchical(const Solution &solution) {
  return !solution.links.empty() && !solution.treeRadiosity.empty() &&
         solution.treeRadiosity.size() == solution.mesh.tree.size();
}

LinksByReceiver indexLinksByReceiver(const Solution &solution, const std::function<bool(const Link &)> &keep) {
  const RadiosityMesh &mesh = solution.mesh;
  LinksByReceiver index;
  index.parent.assign(mesh.tree.size(), -1);
  index.leafOfElement.assign(mesh.elements.size(), -1);
  for (uint32_t t = 0; t < mesh.tree.size(); ++t) {
    const MeshTreeNode &node = mesh.tree[t];
    if (node.isLeaf()) {
      if (node.element >= 0) index.leafOfElement[size_t(node.element)] = int32_t(t);
    } else {
      for (int32_t child : node.children)
        if (child >= 0) index.parent[size_t(child)] = int32_t(t);
    }
  }
  index.links.assign(mesh.tree.size(), {});
  for (uint32_t l = 0; l < solution.links.size(); ++l) {
    const Link &link = solution.links[l];
    if (!keep || keep(link)) index.links[link.receiver].push_back(l);
  }
  return index;
}

}  // namespace radiant
