#include "texture/surface_detail.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace radiant {

namespace {

std::array<double, 2> uvOf(const Scene &scene, int32_t index) {
  return {scene.uvs[2 * size_t(index)], scene.uvs[2 * size_t(index) + 1]};
}

Bands clampedReflectance(Bands rho) {
  for (int b = 0; b < kBandCount; ++b) rho[b] = std::clamp(rho[b], 0.0, kMaxTexturedReflectance);
  return rho;
}

/// Barycentrics (b1, b2) of p's projection onto the triangle's plane.
std::array<double, 2> barycentrics(const Vec3 &p, const Vec3 &p0, const Vec3 &p1, const Vec3 &p2) {
  const Vec3 e1 = p1 - p0, e2 = p2 - p0, d = p - p0;
  const double a = dot(e1, e1), b = dot(e1, e2), c = dot(e2, e2), r1 = dot(d, e1), r2 = dot(d, e2);
  const double det = a * c - b * b;
  if (!(std::abs(det) > 0)) return {0, 0};
  return {(c * r1 - b * r2) / det, (a * r2 - b * r1) / det};
}

/// Blinn (1978): the normal of the surface displaced by d(u, v) along n, to
/// first order, n' ∝ |N| n + d_u (n × p_v) − d_v (n × p_u) with N = p_u × p_v
/// (its sign folded in for mirrored texture coordinates). A flat map leaves n as it is.
Vec3 bumpedNormal(const Vec3 &n, const SurfaceParameterisation &s, double du, double dv) {
  const Vec3 N = cross(s.dpdu, s.dpdv);
  const double sign = dot(N, n) < 0 ? -1.0 : 1.0;
  return normalize(n * length(N) + (cross(n, s.dpdv) * du - cross(n, s.dpdu) * dv) * sign);
}

/// A tangent-space normal map (OpenGL convention: red along +u, green along +v, blue out of the surface).
Vec3 mappedNormal(const Vec3 &n, const SurfaceParameterisation &s, const Bands &texel) {
  Vec3 t = s.dpdu - n * dot(n, s.dpdu);
  if (!(length(t) > 0)) return n;
  t = normalize(t);
  Vec3 b = s.dpdv - n * dot(n, s.dpdv) - t * dot(t, s.dpdv);
  b = length(b) > 0 ? normalize(b) : cross(n, t);
  const Vec3 local{2 * texel[0] - 1, 2 * texel[1] - 1, 2 * texel[2] - 1};
  Vec3 mapped = t * local.x + b * local.y + n * local.z;
  return length(mapped) > 0 ? normalize(mapped) : n;
}

}  // namespace

SurfaceParameterisation surfaceParameterisation(const Scene &scene, const Triangle &t, double b1, double b2) {
  SurfaceParameterisation s;
  const Material &m = scene.materials[t.material];
  const Vec3 &p0 = scene.positions[t.v[0]];
  const Vec3 e1 = scene.positions[t.v[1]] - p0, e2 = scene.positions[t.v[2]] - p0;
  s.hasUv = t.uv[0] >= 0 && t.uv[1] >= 0 && t.uv[2] >= 0;
  std::array<double, 2> uv[3] = {{0, 0}, {1, 0}, {0, 1}};  // without coordinates: the triangle's own frame
  if (s.hasUv)
    for (int k = 0; k < 3; ++k) {
      uv[k] = uvOf(scene, t.uv[k]);
      uv[k][0] *= m.uvScale[0], uv[k][1] *= m.uvScale[1];
    }
  const double b0 = 1 - b1 - b2;
  if (s.hasUv) s.u = b0 * uv[0][0] + b1 * uv[1][0] + b2 * uv[2][0], s.v = b0 * uv[0][1] + b1 * uv[1][1] + b2 * uv[2][1];
  // [e1 e2] = [p_u p_v] [[du1 du2] [dv1 dv2]] (pbrt's triangle partial derivatives).
  const double du1 = uv[1][0] - uv[0][0], dv1 = uv[1][1] - uv[0][1];
  const double du2 = uv[2][0] - uv[0][0], dv2 = uv[2][1] - uv[0][1];
  const double det = du1 * dv2 - du2 * dv1;
  const double area2 = length(cross(e1, e2));
  if (std::abs(det) > 1e-12 * (std::abs(du1 * dv2) + std::abs(du2 * dv1) + 1e-300) && area2 > 0) {
    s.dpdu = (e1 * dv2 - e2 * dv1) / det;
    s.dpdv = (e2 * du1 - e1 * du2) / det;
    s.uvPerMetre = std::sqrt(std::abs(det) / area2);
  } else {  // degenerate texture coordinates: any frame in the plane, no filtering information
    s.dpdu = normalize(e1);
    s.dpdv = cross(normalize(cross(e1, e2)), s.dpdu);
  }
  return s;
}

SurfaceDetail surfaceDetail(const Scene &scene, const Hit &hit, double footprint) {
  const Material &m = scene.materials[hit.material];
  SurfaceDetail detail{m.diffuse, hit.shadingNormal};
  if (!m.hasSurfaceDetail()) return detail;
  const SurfaceParameterisation s = surfaceParameterisation(scene, scene.triangles[hit.triangle], hit.b1, hit.b2);
  if (m.diffuseTextureIndex >= 0) {
    const Texture &texture = scene.textures[m.diffuseTextureIndex];
    detail.diffuse = clampedReflectance(m.diffuse * texture.filtered(s.u, s.v, footprint * s.uvPerMetre));
  }
  if (m.bumpTextureIndex >= 0) {
    const auto [hu, hv] = scene.textures[m.bumpTextureIndex].gradient(s.u, s.v);
    const double metres = m.bumpScale * scene.metresPerUnit;  // height per unit of map value
    detail.shadingNormal = bumpedNormal(hit.shadingNormal, s, metres * hu, metres * hv);
  } else if (m.normalTextureIndex >= 0) {
    detail.shadingNormal = mappedNormal(hit.shadingNormal, s, scene.textures[m.normalTextureIndex].bilinear(s.u, s.v));
  }
  // A shading normal below the surface would let light leak through it: keep it just above.
  const double above = dot(detail.shadingNormal, hit.geometricNormal);
  if (above < 1e-3) detail.shadingNormal = normalize(detail.shadingNormal + hit.geometricNormal * (1e-3 - above));
  return detail;
}

Bands averageDiffuse(const Scene &scene, uint32_t face, std::span<const Vec3> polygon) {
  const Material &m = scene.materials[scene.faces[face].material];
  if (m.diffuseTextureIndex < 0 || polygon.empty()) return m.diffuse;
  // The face's triangles are consecutive in Scene::triangles (Scene::addFace).
  auto first = std::lower_bound(scene.triangles.begin(), scene.triangles.end(), face,
                                [](const Triangle &t, uint32_t f) { return t.face < f; });
  auto last = std::upper_bound(first, scene.triangles.end(), face,
                               [](uint32_t f, const Triangle &t) { return f < t.face; });
  if (first == last) return m.diffuse;
  std::vector<std::array<double, 2>> uvPolygon;
  for (const Vec3 &p : polygon) {
    // The triangle that holds p best (largest smallest barycentric), so a
    // quad split in two maps each corner with its own triangle's coordinates.
    const Triangle *best = &*first;
    std::array<double, 2> bestB{0, 0};
    double bestInside = -INFINITY;
    for (auto t = first; t != last; ++t) {
      auto b = barycentrics(p, scene.positions[t->v[0]], scene.positions[t->v[1]], scene.positions[t->v[2]]);
      double inside = std::min({1 - b[0] - b[1], b[0], b[1]});
      if (inside > bestInside) bestInside = inside, best = &*t, bestB = b;
    }
    SurfaceParameterisation s = surfaceParameterisation(scene, *best, bestB[0], bestB[1]);
    uvPolygon.push_back({s.u, s.v});
  }
  return clampedReflectance(m.diffuse * scene.textures[m.diffuseTextureIndex].average(uvPolygon));
}

}  // namespace radiant
