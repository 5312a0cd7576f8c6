#include "radiosity/transmission.h"

#include <map>

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

namespace {

/// Points spread evenly over an element: the centres of a k × k grid of its
/// bilinear parameters (a quad), or of the k² triangles of its k-fold lattice
/// (a triangle), each standing for the same share of its area.
std::vector<Vec3> spreadPoints(const std::vector<Vec3> &polygon, int k) {
  std::vector<Vec3> points;
  if (polygon.size() == 4) {
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k; ++j) {
        const double s = (i + 0.5) / k, t = (j + 0.5) / k;
        points.push_back(polygon[0] * ((1 - s) * (1 - t)) + polygon[1] * (s * (1 - t)) + polygon[2] * (s * t) +
                         polygon[3] * ((1 - s) * t));
      }
    return points;
  }
  const Vec3 &a = polygon[0], &b = polygon[1], &c = polygon[2];
  for (int i = 0; i < k; ++i)
    for (int j = 0; i + j < k; ++j) {
      // The upward triangle of cell (i, j), and the downward one beside it: their centroids.
      points.push_back(a + (b - a) * ((i + 1.0 / 3) / k) + (c - a) * ((j + 1.0 / 3) / k));
      if (i + j + 1 < k) points.push_back(a + (b - a) * ((i + 2.0 / 3) / k) + (c - a) * ((j + 2.0 / 3) / k));
    }
  return points;
}

}  // namespace

ElementTransmission::ElementTransmission(const Scene &scene, const Solution &solution) {
  const RadiosityMesh &mesh = solution.mesh;
  transmittance_ = solution.transmittance.size() == mesh.elements.size() ? solution.transmittance
                                                                         : elementTransmittance(scene, mesh);
  bool any = false;
  for (const Bands &t : transmittance_) any = any || t.max() > 0;
  if (!any) return;
  outgoing_.assign(mesh.elements.size(), {});
  // Each receiving element pulls the other side's irradiance over its area,
  // sampled at points spread over it: where the two sides are meshed alike
  // (the uniform mesher's) every point lands in the one element over it.
  constexpr int kSpread = 4;
  for (size_t to = 0; to < mesh.elements.size(); ++to) {
    if (transmittance_[to].max() <= 0) continue;
    const int32_t twin = scene.faces[mesh.patchOf(uint32_t(to)).face].twin;
    if (twin < 0 || mesh.patchOfFace[size_t(twin)] < 0) continue;
    const std::vector<Vec3> points = spreadPoints(mesh.polygon(uint32_t(to)), kSpread);
    std::map<uint32_t, double> share;
    for (const Vec3 &p : points) share[mesh.locate(uint32_t(twin), p).element] += 1.0 / double(points.size());
    for (const auto &[from, weight] : share) outgoing_[from].push_back({uint32_t(to), weight});
  }
}

std::vector<std::vector<std::pair<uint32_t, double>>> ElementTransmission::incoming() const {
  std::vector<std::vector<std::pair<uint32_t, double>>> in(outgoing_.size());
  for (size_t from = 0; from < outgoing_.size(); ++from)
    for (const auto &[to, weight] : outgoing_[from]) in[to].push_back({uint32_t(from), weight});
  return in;
}

}  // namespace radiant
