#include "export/baked_mesh.h"

#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include "raytrace/surface_detail.h"

namespace radiant {

namespace {

SurfaceLight meanLight(std::span<const SurfaceLight> lights) {
  SurfaceLight mean;
  for (const SurfaceLight &l : lights) {
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

/// The light at every node, as the `interpolate` display reads it: B̂ (ambient
/// included), L = max(B̂, E)/π, and H such that ρ̄H = B̂ − E at the node, so
/// that a viewer's E + ρ(x)·H reproduces C&W eq. 9.11's E + (B̂ − E)·ρ(x)/ρ̄.
SurfaceLight lightFrom(const Bands &b, const Bands &rho, const Bands &elementsIrradiance, const Bands &emitted) {
  SurfaceLight v;
  v.reflectance = rho;
  for (int c = 0; c < kBandCount; ++c) {
    const double reflected = std::max(b[c] - emitted[c], 0.0);
    v.radiance[c] = (emitted[c] + reflected) * kInvPi;
    v.irradiance[c] = rho[c] > kSmallestReflectance ? reflected / rho[c] : std::max(elementsIrradiance[c], 0.0);
  }
  return v;
}

std::vector<SurfaceLight> nodeLight(const Scene &scene, const Solution &solution) {
  const RadiosityMesh &mesh = solution.mesh;
  const std::vector<Bands> fallback = nodeIrradiance(solution);
  std::vector<SurfaceLight> light(mesh.nodes.size());
  for (size_t n = 0; n < mesh.nodes.size(); ++n) {
    const Material &material = scene.materials[mesh.patches[mesh.nodePatch[n]].material];
    light[n] = lightFrom(solution.nodeRadiosity[n], solution.nodeReflectance[n], fallback[n], material.emission * kPi);
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

/// The T-vertices on each edge of the mesh (RadiosityMesh::tVertices): the
/// nodes of finer elements lying inside a coarser element's edge. A coarse
/// element's triangles must pass through them, or the finer neighbours'
/// triangles leave pinholes (cracks) along the edge.
class EdgePoints {
 public:
  explicit EdgePoints(const RadiosityMesh &mesh) {
    for (const RadiosityMesh::TVertex &t : mesh.tVertices) points_[key(t.edgeStart, t.edgeEnd)].push_back(t);
  }

  /// Appends the nodes strictly inside edge a → b, in order from a, the
  /// T-vertices of its halves included (a T-vertex's own edge may be part of a longer one).
  void append(uint32_t a, uint32_t b, std::vector<uint32_t> &out, int depth = 0) const {
    auto found = points_.find(key(a, b));
    if (found == points_.end() || depth > kMaxSolutionTreeDepth) return;
    std::vector<std::pair<double, uint32_t>> inside;
    for (const RadiosityMesh::TVertex &t : found->second)
      inside.push_back({t.edgeStart == a ? t.t : 1.0 - t.t, t.node});
    std::sort(inside.begin(), inside.end());
    uint32_t from = a;
    for (const auto &[along, node] : inside) {
      append(from, node, out, depth + 1);
      out.push_back(node);
      from = node;
    }
    append(from, b, out, depth + 1);
  }

 private:
  static uint64_t key(uint32_t a, uint32_t b) { return uint64_t(std::min(a, b)) << 32 | std::max(a, b); }
  std::unordered_map<uint64_t, std::vector<RadiosityMesh::TVertex>> points_;
};

class PrimitiveBuilder {
 public:
  explicit PrimitiveBuilder(const Scene &scene) : scene_(scene), primitiveOfMaterial_(scene.materials.size(), -1) {}

  int32_t indexOf(uint32_t material) const { return primitiveOfMaterial_[material]; }

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
                     const SurfaceLight &light) {
    const uint32_t index = uint32_t(p.vertexCount());
    for (int c = 0; c < 3; ++c) {
      p.positions.push_back(float(position[c]));
      p.normals.push_back(float(normal[c]));
      p.radiance.push_back(float(light.radiance[c]));
      p.irradiance.push_back(float(light.irradiance[c]));
      p.reflectance.push_back(float(light.reflectance[c]));
    }
    p.faces.push_back(face);
    if (p.hasUv) {
      const auto uv = textureCoordinatesAt(scene_, face, position);
      p.uvs.push_back(float(uv[0]));
      p.uvs.push_back(float(uv[1]));
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
  std::vector<int32_t> primitiveOfMaterial_;
  std::vector<BakedPrimitive> primitives_;
};

}  // namespace

std::vector<Bands> nodeIrradiance(const Solution &solution) {
  std::vector<Bands> elementIrradiance(solution.elementCount());
  for (uint32_t e = 0; e < solution.elementCount(); ++e)
    elementIrradiance[e] = solution.irradiance[e] + solution.ambient;
  return solution.nodeValues(elementIrradiance);
}

SurfaceLight surfaceLightAt(const Solution &solution, const std::vector<Bands> &nodeIrradiance, const MeshLocation &at,
                            const Bands &emitted) {
  return lightFrom(solution.interpolate(solution.nodeRadiosity, at), solution.interpolate(solution.nodeReflectance, at),
                   solution.interpolate(nodeIrradiance, at), emitted);
}

BakedMesh bakeSolution(const Scene &scene, const Solution &solution, const DisplayLinearFunction &displayLinear) {
  const RadiosityMesh &mesh = solution.mesh;
  const std::vector<SurfaceLight> light = nodeLight(scene, solution);
  PrimitiveBuilder builder(scene);
  constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
  // A node is a vertex of its patch's primitive, and of a neighbour's when it is a T-vertex on its edge.
  std::vector<uint32_t> vertexOfNode(mesh.nodes.size(), kNone);
  std::vector<int32_t> primitiveOfNode(mesh.nodes.size(), -1);
  const EdgePoints edgePoints(mesh);
  std::vector<uint32_t> boundary;
  for (uint32_t e = 0; e < mesh.elements.size(); ++e) {
    const Element &element = mesh.elements[e];
    const Patch &patch = mesh.patches[element.patch];
    BakedPrimitive &p = builder.primitive(patch.material);
    const int32_t primitive = builder.indexOf(patch.material);
    auto vertex = [&](uint32_t node) {
      if (vertexOfNode[node] == kNone || primitiveOfNode[node] != primitive) {
        vertexOfNode[node] = builder.addVertex(p, mesh.nodes[node], patch.normal, patch.face, light[node]);
        primitiveOfNode[node] = primitive;
      }
      return vertexOfNode[node];
    };
    // The element's outline: its corners and the T-vertices of finer neighbours on its edges.
    boundary.clear();
    for (int k = 0; k < element.vertexCount; ++k) {
      boundary.push_back(element.nodes[size_t(k)]);
      edgePoints.append(element.nodes[size_t(k)], element.nodes[size_t((k + 1) % element.vertexCount)], boundary);
    }
    // A node of another patch may sit on this element's corner (the pieces of a cut face): one of them.
    boundary.erase(std::unique(boundary.begin(), boundary.end(),
                               [&](uint32_t a, uint32_t b) { return length(mesh.nodes[a] - mesh.nodes[b]) < 1e-9; }),
                   boundary.end());
    while (boundary.size() > 3 && length(mesh.nodes[boundary.back()] - mesh.nodes[boundary.front()]) < 1e-9)
      boundary.pop_back();
    if (boundary.size() == 3) {
      for (uint32_t node : boundary) p.indices.push_back(vertex(node));
      continue;
    }
    // A fan around the centre, which holds the corners' mean (bilinear's and barycentric's value there).
    std::array<SurfaceLight, 4> corners;
    Vec3 centre;
    for (int k = 0; k < element.vertexCount; ++k) {
      corners[size_t(k)] = light[element.nodes[size_t(k)]];
      centre += mesh.nodes[element.nodes[size_t(k)]] * (1.0 / element.vertexCount);
    }
    const uint32_t c = builder.addVertex(p, centre, patch.normal, patch.face,
                                         meanLight(std::span(corners.data(), size_t(element.vertexCount))));
    for (size_t k = 0; k < boundary.size(); ++k)
      p.indices.insert(p.indices.end(), {c, vertex(boundary[k]), vertex(boundary[(k + 1) % boundary.size()])});
  }
  // Mirrors and glass have no patches: their triangles, with no light, so the geometry is whole.
  const SurfaceLight dark{};
  for (const Triangle &t : scene.triangles) {
    const Material &material = scene.materials[t.material];
    if (!material.isSpecular() || (t.face < mesh.patchOfFace.size() && mesh.patchOfFace[t.face] >= 0)) continue;
    BakedPrimitive &p = builder.primitive(t.material);
    const Vec3 normal = scene.triangleNormal(t);
    for (uint32_t k : t.v) p.indices.push_back(builder.addVertex(p, scene.positions[k], normal, t.face, dark));
  }
  BakedMesh baked;
  baked.primitives = builder.take();
  baked.elements = mesh.elements.size();
  if (displayLinear) applyDisplayColours(baked, displayLinear);
  return baked;
}

void applyDisplayColours(BakedMesh &baked, const DisplayLinearFunction &displayLinear) {
  for (BakedPrimitive &p : baked.primitives) {
    p.colour.assign(p.radiance.size(), 0.0f);
    for (size_t v = 0; v < p.vertexCount(); ++v) {
      double display[3] = {0, 0, 0};
      displayLinear(&p.radiance[3 * v], display);
      for (size_t c = 0; c < 3; ++c) {
        const double rho = p.reflectance[3 * v + c];
        p.colour[3 * v + c] = rho > 0 ? float(std::clamp(display[c] / rho, 0.0, 1.0)) : 0.0f;
      }
    }
  }
}

BakedMesh resampleLight(const BakedMesh &baked, const Scene &scene, const Solution &solution) {
  const RadiosityMesh &mesh = solution.mesh;
  const std::vector<Bands> fallback = nodeIrradiance(solution);
  BakedMesh out = baked;
  for (BakedPrimitive &p : out.primitives) {
    const Bands emitted = scene.materials[p.material].emission * kPi;
    for (size_t v = 0; v < p.vertexCount(); ++v) {
      const uint32_t face = p.faces[v];
      SurfaceLight light;
      if (face < mesh.patchOfFace.size() && mesh.patchOfFace[face] >= 0) {
        const MeshLocation at =
            mesh.locate(face, Vec3(p.positions[3 * v], p.positions[3 * v + 1], p.positions[3 * v + 2]));
        light = surfaceLightAt(solution, fallback, at, emitted);
      }
      for (size_t c = 0; c < 3; ++c) {
        p.radiance[3 * v + c] = float(light.radiance[int(c)]);
        p.irradiance[3 * v + c] = float(light.irradiance[int(c)]);
        p.reflectance[3 * v + c] = float(light.reflectance[int(c)]);
      }
    }
  }
  return out;
}

BakedMesh combineSpectralPasses(const std::vector<BakedMesh> &passes, const Scene &scene, WhiteBalance balance) {
  if (passes.empty() || int(passes.size()) != scene.spectral.passCount())
    throw std::logic_error("combineSpectralPasses: one baked mesh per pass expected");
  const BandColourMatching matching(scene.spectral.wavelengths);
  const std::vector<Vec3> weights = matching.linearSrgbWeights(balance);
  BakedMesh rgb = passes[0];
  for (size_t q = 0; q < rgb.primitives.size(); ++q) {
    BakedPrimitive &out = rgb.primitives[q];
    const Bands diffuse = scene.materials[out.material].diffuse;
    for (size_t v = 0; v < out.vertexCount(); ++v) {
      Vec3 radiance, irradiance, reflected;
      for (int i = 0; i < matching.bandCount(); ++i) {
        const BakedPrimitive &pass = passes[size_t(i / kBandCount)].primitives[q];
        const size_t k = 3 * v + size_t(i % kBandCount);
        radiance += weights[size_t(i)] * double(pass.radiance[k]);
        irradiance += weights[size_t(i)] * double(pass.irradiance[k]);
        reflected += weights[size_t(i)] * (double(pass.reflectance[k]) * pass.irradiance[k]);
      }
      for (int c = 0; c < 3; ++c) {
        out.radiance[3 * v + size_t(c)] = float(radiance[c]);
        out.irradiance[3 * v + size_t(c)] = float(std::max(irradiance[c], 0.0));
        out.reflectance[3 * v + size_t(c)] =
            float(irradiance[c] > 1e-12 ? std::clamp(reflected[c] / irradiance[c], 0.0, 1.0) : diffuse[c]);
      }
    }
  }
  return rgb;
}

}  // namespace radiant
