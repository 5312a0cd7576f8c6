#include "radiosity/transmission.h"

namespace radiant {

std::vector<Bands> elementTransmittance(const Scene &scene, const RadiosityMesh &mesh) {
  std::vector<Bands> t(mesh.elements.size(), Bands(0.0));
  for (size_t e = 0; e < mesh.elements.size(); ++e) {
    const Material &m = scene.materials[mesh.patchOf(uint32_t(e)).material];
    if (m.kind == MaterialKind::Lambertian || m.kind == MaterialKind::Glossy) t[e] = m.transmittance;
  }
  return t;
}

int32_t oppositePatch(const Scene &scene, const RadiosityMesh &mesh, uint32_t patch) {
  const Patch &p = mesh.patches[patch];
  const int32_t twin = scene.faces[p.face].twin;
  if (twin < 0 || size_t(twin) >= mesh.patchOfFace.size() || mesh.patchOfFace[size_t(twin)] < 0) return -1;
  Vec3 centre;
  for (int k = 0; k < p.vertexCount; ++k) centre += p.corners[k] / double(p.vertexCount);
  return mesh.patchAt(uint32_t(twin), centre);
}

ElementTransmission::ElementTransmission(const Scene &scene, const Solution &solution) {
  const RadiosityMesh &mesh = solution.mesh;
  transmittance_ = solution.transmittance.size() == mesh.elements.size() ? solution.transmittance
                                                                         : elementTransmittance(scene, mesh);
  bool any = false;
  for (const Bands &t : transmittance_) any = any || t.max() > 0;
  if (!any) return;
  to_.assign(mesh.elements.size(), -1);
  weight_.assign(mesh.elements.size(), 0.0);
  for (size_t e = 0; e < mesh.elements.size(); ++e) {
    const int32_t twin = scene.faces[mesh.patchOf(uint32_t(e)).face].twin;
    if (twin < 0 || mesh.patchOfFace[size_t(twin)] < 0) continue;
    const uint32_t to = mesh.locate(uint32_t(twin), mesh.elements[e].centre).element;
    if (transmittance_[to].max() <= 0) continue;
    to_[e] = int32_t(to);
    weight_[e] = mesh.elements[e].area / mesh.elements[to].area;
  }
}

std::vector<std::vector<std::pair<uint32_t, double>>> ElementTransmission::incoming() const {
  std::vector<std::vector<std::pair<uint32_t, double>>> in(to_.size());
  for (size_t e = 0; e < to_.size(); ++e)
    if (to_[e] >= 0) in[size_t(to_[e])].push_back({uint32_t(e), weight_[e]});
  return in;
}

}  // namespace radiant
