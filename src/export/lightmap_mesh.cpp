#include "export/lightmap_mesh.h"

#include <algorithm>
#include <map>
#include <tuple>

#include "raytrace/surface_detail.h"

namespace radiant {

namespace {

/// Appends the material's texture coordinates (uvScale applied) at corner `k` of a scene triangle.
void appendTextureCoordinates(const Scene &scene, const Triangle &triangle, int k, BakedPrimitive &p) {
  constexpr double kCornerBarycentrics[3][2] = {{0, 0}, {1, 0}, {0, 1}};  // (b1, b2) of corners 0, 1, 2
  const SurfaceParameterisation s =
      surfaceParameterisation(scene, triangle, kCornerBarycentrics[k][0], kCornerBarycentrics[k][1]);
  p.uvs.push_back(float(s.u));
  p.uvs.push_back(float(s.v));
}

}  // namespace

BakedMesh lightmapMesh(const Scene &scene, std::span<const LightmapTriangle> triangles, const LightmapAtlas &atlas,
                       size_t elements) {
  std::vector<int32_t> primitiveOfMaterial(scene.materials.size(), -1);
  BakedMesh baked;
  baked.elements = elements;
  auto primitive = [&](uint32_t material) -> BakedPrimitive & {
    int32_t &index = primitiveOfMaterial[material];
    if (index < 0) {
      index = int32_t(baked.primitives.size());
      baked.primitives.emplace_back();
      baked.primitives.back().material = material;
      baked.primitives.back().hasUv = scene.materials[material].diffuseTextureIndex >= 0;
    }
    return baked.primitives[size_t(index)];
  };
  // A vertex per (primitive, chart, scene vertex, texture coordinate): the triangles of a chart share it.
  std::map<std::tuple<uint32_t, int32_t, uint32_t, int32_t>, uint32_t> vertexOf;
  std::vector<std::vector<Vec3>> normalsOfPrimitive;  // per primitive and vertex: the area-weighted normal sum
  for (size_t t = 0; t < triangles.size(); ++t) {
    const int32_t chart = atlas.chartOfTriangle[t];
    if (chart < 0) continue;  // no area: nothing to draw
    const LightmapTriangle &lt = triangles[t];
    const Triangle &triangle = scene.triangles[lt.triangle];
    const uint32_t material = scene.faces[lt.face].material;
    BakedPrimitive &p = primitive(material);
    const size_t primitiveIndex = size_t(primitiveOfMaterial[material]);
    if (normalsOfPrimitive.size() <= primitiveIndex) normalsOfPrimitive.resize(primitiveIndex + 1);
    std::vector<Vec3> &normals = normalsOfPrimitive[primitiveIndex];
    const Vec3 areaNormal = cross(lt.corners[1] - lt.corners[0], lt.corners[2] - lt.corners[0]);
    for (int k = 0; k < 3; ++k) {
      auto [found, added] = vertexOf.emplace(
          std::make_tuple(uint32_t(primitiveIndex), chart, triangle.v[k], triangle.uv[k]), uint32_t(p.vertexCount()));
      if (added) {
        const Vec3 &position = lt.corners[k];
        for (int c = 0; c < 3; ++c) p.positions.push_back(float(position[c]));
        const double *uv = &atlas.texelCoordinates[6 * t + 2 * size_t(k)];
        p.lightmapUvs.push_back(float(uv[0] / atlas.width));
        p.lightmapUvs.push_back(float(uv[1] / atlas.height));
        if (p.hasUv) appendTextureCoordinates(scene, triangle, k, p);
        p.faces.push_back(lt.face);
        normals.push_back(Vec3());
      }
      normals[found->second] += areaNormal;
      p.indices.push_back(found->second);
    }
  }
  for (size_t q = 0; q < baked.primitives.size(); ++q) {
    BakedPrimitive &p = baked.primitives[q];
    for (const Vec3 &n : normalsOfPrimitive[q]) {
      const Vec3 unit = length(n) > 0 ? normalize(n) : Vec3(0, 0, 1);
      for (int c = 0; c < 3; ++c) p.normals.push_back(float(unit[c]));
    }
  }
  // Mirrors and glass: no light of their own in the solution, black for a viewer that shows only baked light.
  std::vector<bool> lit(scene.faces.size(), false);
  for (const LightmapTriangle &lt : triangles) lit[lt.face] = true;
  for (const Triangle &t : scene.triangles) {
    if (!scene.materials[t.material].isSpecular() || lit[t.face]) continue;
    BakedPrimitive &p = primitive(t.material);
    const Vec3 normal = scene.triangleNormal(t);
    for (int k = 0; k < 3; ++k) {
      p.indices.push_back(uint32_t(p.vertexCount()));
      for (int c = 0; c < 3; ++c) {
        p.positions.push_back(float(scene.positions[t.v[k]][c]));
        p.normals.push_back(float(normal[c]));
        p.colour.push_back(0.0f);
      }
      if (p.hasUv) appendTextureCoordinates(scene, t, k, p);
      p.faces.push_back(t.face);
    }
  }
  std::sort(baked.primitives.begin(), baked.primitives.end(),
            [](const BakedPrimitive &a, const BakedPrimitive &b) { return a.material < b.material; });
  return baked;
}

}  // namespace radiant
