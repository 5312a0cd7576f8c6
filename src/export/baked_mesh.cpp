#include "export/baked_mesh.h"

#include <algorithm>
#include <array>
#include <limits>

#include "raytrace/surface_detail.h"

namespace radiant {

namespace {

/// What a vertex carries, in Bands.
struct VertexLight {
  Bands radiance, irradiance, reflectance;
};

VertexLight meanLight(std::span<const VertexLight> lights) {
  VertexLight mean;
  for (const VertexLight &l : lights) {
    mean.radiance += l.radiance;
    mean.irradiance += l.irradiance;
    mean.reflectance += l.reflectance;
  }
  const double w = 1.0 / double(lights.size());
  mean.radiance *= w;
  mean.irradiance *= w;
  mean.reflectance *= w;
  return mean;
}

/// Below this ρ̄ a band reflects (almost) nothing: its irradiance cannot be
/// recovered from B − E, and is taken from the elements' own H instead.
constexpr double kSmallestReflectance = 1e-4;

/// The light at every node, as the `interpolate` display reads it: B̂ (ambient
/// included), L = max(B̂, E)/π, and H such that ρ̄H = B̂ − E at the node, so
/// that a viewer's E + ρ(x)·H reproduces C&W eq. 9.11's E + (B̂ − E)·ρ(x)/ρ̄.
std::vector<VertexLight> nodeLight(const Scene &scene, const Solution &solution) {
  const RadiosityMesh &mesh = solution.mesh;
  std::vector<Bands> elementIrradiance(solution.elementCount());
  for (uint32_t e = 0; e < solution.elementCount(); ++e)
    elementIrradiance[e] = solution.irradiance[e] + solution.ambient;
  const std::vector<Bands> fallback = solution.nodeValues(elementIrradiance);
  std::vector<VertexLight> light(mesh.nodes.size());
  for (size_t n = 0; n < mesh.nodes.size(); ++n) {
    const Material &material = scene.materials[mesh.patches[mesh.nodePatch[n]].material];
    const Bands emitted = material.emission * kPi;
    const Bands &b = solution.nodeRadiosity[n];
    const Bands &rho = solution.nodeReflectance[n];
    VertexLight &v = light[n];
    v.reflectance = rho;
    for (int c = 0; c < kBandCount; ++c) {
      const double reflected = std::max(b[c] - emitted[c], 0.0);
      v.radiance[c] = (emitted[c] + reflected) * kInvPi;
      v.irradiance[c] = rho[c] > kSmallestReflectance ? reflected / rho[c] : std::max(fallback[n][c], 0.0);
    }
  }
  return light;
}

/// The material's texture coordinates at a point of a face (uvScale applied),
/// from the face's triangle that contains it (the map is affine per triangle).
std::array<double, 2> textureCoordinatesAt(const Scene &scene, uint32_t face, const Vec3 &p) {
  auto first = std::lower_bound(scene.triangles.begin(), scene.triangles.end(), face,
                                [](const Triangle &t, uint32_t f) { return t.face < f; });
  const Triangle *best = nullptr;
  double bestInside = -std::numeric_limits<double>::infinity(), bestB1 = 0, bestB2 = 0;
  for (auto t = first; t != scene.triangles.end() && t->face == face; ++t) {
    const Vec3 &p0 = scene.positions[t->v[0]], &p1 = scene.positions[t->v[1]], &p2 = scene.positions[t->v[2]];
    const Vec3 e1 = p1 - p0, e2 = p2 - p0, d = p - p0;
    const double a = dot(e1, e1), b = dot(e1, e2), c = dot(e2, e2), r1 = dot(d, e1), r2 = dot(d, e2);
    const double det = a * c - b * b;
    if (!(std::abs(det) > 0)) continue;
    const double b1 = (c * r1 - b * r2) / det, b2 = (a * r2 - b * r1) / det;
    const double inside = std::min({b1, b2, 1 - b1 - b2});  // ≥ 0 inside; the largest is the containing one
    if (inside > bestInside) bestInside = inside, best = &*t, bestB1 = b1, bestB2 = b2;
  }
  if (!best) return {0, 0};
  const SurfaceParameterisation s = surfaceParameterisation(scene, *best, bestB1, bestB2);
  return {s.u, s.v};
}

class PrimitiveBuilder {
 public:
  PrimitiveBuilder(const Scene &scene, const DisplayLinearFunction &displayLinear)
      : scene_(scene), displayLinear_(displayLinear), primitiveOfMaterial_(scene.materials.size(), -1) {}

  BakedPrimitive &primitive(uint32_t material) {
    int32_t &index = primitiveOfMaterial_[material];
    if (index < 0) {
      index = int32_t(primitives_.size());
      primitives_.emplace_back();
      primitives_.back().material = material;
      primitives_.back().hasUv = scene_.materials[material].diffuseTextureIndex >= 0;
    }
    return primitives_[size_t(index)];
  }

  uint32_t addVertex(BakedPrimitive &p, const Vec3 &position, const Vec3 &normal, uint32_t face,
                     const VertexLight &light) {
    const uint32_t index = uint32_t(p.vertexCount());
    for (int c = 0; c < 3; ++c) {
      p.positions.push_back(float(position[c]));
      p.normals.push_back(float(normal[c]));
      p.radiance.push_back(float(light.radiance[c]));
      p.irradiance.push_back(float(light.irradiance[c]));
    }
    if (p.hasUv) {
      const auto uv = textureCoordinatesAt(scene_, face, position);
      p.uvs.push_back(float(uv[0]));
      p.uvs.push_back(float(uv[1]));
    }
    // COLOR_0 = T(L)/ρ̄: an unlit viewer multiplies it by the base colour ρ (docs/export.md).
    const float radiance[3] = {float(light.radiance[0]), float(light.radiance[1]), float(light.radiance[2])};
    double display[3] = {0, 0, 0};
    if (displayLinear_) displayLinear_(radiance, display);
    for (int c = 0; c < 3; ++c) {
      const double rho = light.reflectance[c];
      p.colour.push_back(rho > 0 ? float(std::clamp(display[c] / rho, 0.0, 1.0)) : 0.0f);
    }
    return index;
  }

  std::vector<BakedPrimitive> take() {
    std::vector<BakedPrimitive> out = std::move(primitives_);
    std::sort(out.begin(), out.end(),
              [](const BakedPrimitive &a, const BakedPrimitive &b) { return a.material < b.material; });
    return out;
  }

 private:
  const Scene &scene_;
  const DisplayLinearFunction &displayLinear_;
  std::vector<int32_t> primitiveOfMaterial_;
  std::vector<BakedPrimitive> primitives_;
};

}  // namespace

BakedMesh bakeSolution(const Scene &scene, const Solution &solution, const DisplayLinearFunction &displayLinear) {
  const RadiosityMesh &mesh = solution.mesh;
  const std::vector<VertexLight> light = nodeLight(scene, solution);
  PrimitiveBuilder builder(scene, displayLinear);
  constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
  // Nodes belong to one patch, hence to one material and one primitive.
  std::vector<uint32_t> vertexOfNode(mesh.nodes.size(), kNone);
  for (uint32_t e = 0; e < mesh.elements.size(); ++e) {
    const Element &element = mesh.elements[e];
    const Patch &patch = mesh.patches[element.patch];
    BakedPrimitive &p = builder.primitive(patch.material);
    std::array<uint32_t, 4> v{};
    for (int k = 0; k < element.vertexCount; ++k) {
      const uint32_t node = element.nodes[size_t(k)];
      if (vertexOfNode[node] == kNone)
        vertexOfNode[node] = builder.addVertex(p, mesh.nodes[node], patch.normal, patch.face, light[node]);
      v[size_t(k)] = vertexOfNode[node];
    }
    if (element.vertexCount == 3) {
      p.indices.insert(p.indices.end(), {v[0], v[1], v[2]});
      continue;
    }
    // A quad: four triangles around its centre, which holds the corners' mean (bilinear's value there).
    std::array<VertexLight, 4> corners;
    Vec3 centre;
    for (size_t k = 0; k < 4; ++k) {
      corners[k] = light[element.nodes[k]];
      centre += mesh.nodes[element.nodes[k]] * 0.25;
    }
    const uint32_t c = builder.addVertex(p, centre, patch.normal, patch.face, meanLight(corners));
    for (size_t k = 0; k < 4; ++k) p.indices.insert(p.indices.end(), {c, v[k], v[(k + 1) % 4]});
  }
  // Mirrors and glass have no patches: their triangles, with no light, so the geometry is whole.
  const VertexLight dark{};
  for (const Triangle &t : scene.triangles) {
    const Material &material = scene.materials[t.material];
    if (!material.isDelta() || (t.face < mesh.patchOfFace.size() && mesh.patchOfFace[t.face] >= 0)) continue;
    BakedPrimitive &p = builder.primitive(t.material);
    const Vec3 normal = scene.triangleNormal(t);
    for (uint32_t k : t.v) p.indices.push_back(builder.addVertex(p, scene.positions[k], normal, t.face, dark));
  }
  BakedMesh baked;
  baked.primitives = builder.take();
  baked.elements = mesh.elements.size();
  return baked;
}

}  // namespace radiant
