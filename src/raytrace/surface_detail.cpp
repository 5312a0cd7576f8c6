#include "raytrace/surface_detail.h"

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
  if (!s.hasUv) {
    // Without texture coordinates a bump has no direction to tilt in: the
    // triangle's own frame would facet the surface. Only the texture applies.
  } else if (m.bumpTextureIndex >= 0) {
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
  const Texture &texture = scene.textures[m.diffuseTextureIndex];
  // The face's triangles are consecutive in Scene::triangles (Scene::addFace).
  auto first = std::lower_bound(scene.triangles.begin(), scene.triangles.end(), face,
                                [](const Triangle &t, uint32_t f) { return t.face < f; });
  auto last =
      std::upper_bound(first, scene.triangles.end(), face, [](uint32_t f, const Triangle &t) { return f < t.face; });
  if (first == last) return m.diffuse;
  // The texture map is affine on each triangle, not across a quad's diagonal
  // (review): cut the polygon by each triangle, average each piece in its
  // own texture coordinates, and weight the pieces by their surface area.
  Bands sum(0.0);
  double area = 0;
  for (auto t = first; t != last; ++t) {
    const Vec3 p[3] = {scene.positions[t->v[0]], scene.positions[t->v[1]], scene.positions[t->v[2]]};
    const Vec3 n = cross(p[1] - p[0], p[2] - p[0]);
    std::vector<Vec3> piece(polygon.begin(), polygon.end());
    for (int e = 0; e < 3 && piece.size() >= 3; ++e) {  // Sutherland–Hodgman against each edge's inner half-plane
      const Vec3 a = p[e], b = p[(e + 1) % 3];
      auto inside = [&](const Vec3 &q) { return dot(cross(b - a, q - a), n); };
      std::vector<Vec3> clipped;
      for (size_t i = 0; i < piece.size(); ++i) {
        const Vec3 &c = piece[i], &d = piece[(i + 1) % piece.size()];
        const double sc = inside(c), sd = inside(d);
        if (sc >= 0) clipped.push_back(c);
        if ((sc >= 0) != (sd >= 0)) clipped.push_back(c + (d - c) * (sc / (sc - sd)));
      }
      piece = std::move(clipped);
    }
    if (piece.size() < 3) continue;
    double pieceArea = 0;
    for (size_t i = 1; i + 1 < piece.size(); ++i)
      pieceArea += 0.5 * length(cross(piece[i] - piece[0], piece[i + 1] - piece[0]));
    if (!(pieceArea > 0)) continue;
    std::vector<std::array<double, 2>> uvPiece;
    for (const Vec3 &q : piece) {
      const auto b = barycentrics(q, p[0], p[1], p[2]);
      const SurfaceParameterisation s = surfaceParameterisation(scene, *t, b[0], b[1]);
      uvPiece.push_back({s.u, s.v});
    }
    sum += texture.average(uvPiece) * pieceArea;
    area += pieceArea;
  }
  if (!(area > 0)) {  // a degenerate polygon: the texture at its first point
    const auto b = barycentrics(polygon[0], scene.positions[first->v[0]], scene.positions[first->v[1]],
                                scene.positions[first->v[2]]);
    const SurfaceParameterisation s = surfaceParameterisation(scene, *first, b[0], b[1]);
    return clampedReflectance(m.diffuse * texture.bilinear(s.u, s.v));
  }
  return clampedReflectance(m.diffuse * (sum / area));
}

}  // namespace radiant
