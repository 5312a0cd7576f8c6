#include "radiosity/solution.h"

namespace radiant {

Solution initialSolution(const Scene &scene, RadiosityMesh mesh) {
  Solution s;
  const size_t n = mesh.elements.size();
  s.reflectance.resize(n);
  s.emission.resize(n);
  for (size_t e = 0; e < n; ++e) {
    const Material &m = scene.materials[mesh.patchOf(static_cast<uint32_t>(e)).material];
    // Only the diffuse part takes part in radiosity; mirrors and glass are left
    // to the per-pixel passes (their diffuse reflectance is 0).
    s.reflectance[e] = m.kind == MaterialKind::Lambertian || m.kind == MaterialKind::Glossy ? m.diffuse : Bands(0.0);
    s.emission[e] = m.emission * kPi;
  }
  s.radiosity = s.emission;
  s.direct.assign(n, Bands(0.0));
  s.indirect.assign(n, Bands(0.0));
  s.unshot = s.emission;
  s.irradiance.assign(n, Bands(0.0));
  s.mesh = std::move(mesh);
  for (size_t e = 0; e < n; ++e) s.stats.emittedPower += s.emission[e] * s.mesh.elements[e].area;
  s.updateNodesAndErrors();
  return s;
}

Bands Solution::interpolatedRadiosity(const MeshLocation &location) const {
  const Element &e = mesh.elements[location.element];
  std::array<double, 4> w = mesh.nodeWeights(location);
  Bands b(0.0);
  for (int k = 0; k < e.vertexCount; ++k) b += nodeRadiosity[e.nodes[k]] * w[k];
  return b;
}

void Solution::updateNodesAndErrors() {
  std::vector<double> weight(mesh.nodes.size(), 0.0);
  nodeRadiosity.assign(mesh.nodes.size(), Bands(0.0));
  for (uint32_t e = 0; e < mesh.elements.size(); ++e) {
    const Element &element = mesh.elements[e];
    Bands b = displayRadiosity(e);
    for (int k = 0; k < element.vertexCount; ++k) {
      nodeRadiosity[element.nodes[k]] += b * element.area;
      weight[element.nodes[k]] += element.area;
    }
  }
  for (size_t v = 0; v < nodeRadiosity.size(); ++v)
    if (weight[v] > 0) nodeRadiosity[v] = nodeRadiosity[v] / weight[v];
  for (const RadiosityMesh::TVertex &t : mesh.tVertices)
    nodeRadiosity[t.node] = (nodeRadiosity[t.edgeStart] + nodeRadiosity[t.edgeEnd]) * 0.5;
  // Gradient estimate (C&W ch. 6, Cohen et al. 1986): how far the nodes around
  // an element stray from its own value, relative to it. Large where the
  // constant element misrepresents a shadow edge or a steep falloff.
  errorEstimate.assign(mesh.elements.size(), 0.0);
  for (uint32_t e = 0; e < mesh.elements.size(); ++e) {
    const Element &element = mesh.elements[e];
    double b = displayRadiosity(e).luminance();
    double worst = 0;
    for (int k = 0; k < element.vertexCount; ++k)
      worst = std::max(worst, std::abs(nodeRadiosity[element.nodes[k]].luminance() - b));
    errorEstimate[e] = b > 0 ? worst / b : (worst > 0 ? 1.0 : 0.0);
  }
}

}  // namespace radiant
