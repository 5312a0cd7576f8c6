// Building faces from input polygons and analytic shapes (see load_detail.h).

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "scene/load_detail.h"

namespace radiant::detail {

uint32_t defaultMaterialIndex(Scene &scene) {
  int found = findMaterial(scene, "default");
  if (found >= 0) return static_cast<uint32_t>(found);
  Material grey;
  grey.name = "default";
  grey.kind = MaterialKind::Lambertian;
  grey.diffuse = Bands(0.5);
  scene.materials.push_back(grey);
  return static_cast<uint32_t>(scene.materials.size() - 1);
}

int findMaterial(const Scene &scene, const std::string &name) {
  for (size_t i = 0; i < scene.materials.size(); ++i)
    if (scene.materials[i].name == name) return static_cast<int>(i);
  return -1;
}

namespace {

Vec3 newellNormal(const Scene &scene, const std::vector<uint32_t> &vertices) {
  Vec3 n;
  for (size_t k = 0; k < vertices.size(); ++k) {
    const Vec3 &a = scene.positions[vertices[k]];
    const Vec3 &b = scene.positions[vertices[(k + 1) % vertices.size()]];
    n += Vec3{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
  }
  return n;
}

void addPiece(Scene &scene, const std::vector<uint32_t> &vertices, const std::vector<int32_t> &uvs,
              const std::vector<int32_t> &normals, std::initializer_list<int> corners, uint32_t material,
              uint32_t object) {
  Face face;
  face.vertexCount = static_cast<int>(corners.size());
  int slot = 0;
  for (int corner : corners) {
    face.vertices[slot] = vertices[corner];
    face.uvs[slot] = uvs[corner];
    face.normals[slot] = normals[corner];
    ++slot;
  }
  face.material = material;
  face.object = object;
  scene.addFace(face);
}

}  // namespace

void addPolygon(Scene &scene, const std::vector<uint32_t> &verticesIn, const std::vector<int32_t> &uvsIn,
                const std::vector<int32_t> &normalsIn, uint32_t material, uint32_t object, bool flipWinding) {
  const size_t n = verticesIn.size();
  auto drop = [&](const std::vector<uint32_t> &corners, const char *reason) {
    std::vector<Vec3> points;
    for (uint32_t v : corners) points.push_back(scene.positions[v]);
    scene.dropDegenerateFace(points, object, reason);
  };
  if (n < 3) {
    drop(verticesIn, "fewer than three corners");
    return;
  }
  // Reversing all but the first vertex turns the front to the back. A vertex
  // at the same place as the one before it ("f 1 2 2 3", or two indices of one
  // point) is dropped: it adds a zero-length edge, which a quad's mesher
  // cannot subdivide.
  std::vector<uint32_t> vertices;
  std::vector<int32_t> uvs, normals;
  for (size_t k = 0; k < n; ++k) {
    size_t from = flipWinding ? (n - k) % n : k;
    if (!vertices.empty() && scene.positions[verticesIn[from]] == scene.positions[vertices.back()]) continue;
    vertices.push_back(verticesIn[from]);
    uvs.push_back(uvsIn.empty() ? -1 : uvsIn[from]);
    normals.push_back(normalsIn.empty() ? -1 : normalsIn[from]);
  }
  while (vertices.size() > 1 && scene.positions[vertices.back()] == scene.positions[vertices.front()]) {
    vertices.pop_back(), uvs.pop_back(), normals.pop_back();
  }
  if (vertices.size() < 3) {
    drop(verticesIn, "fewer than three distinct corners");
    return;
  }
  const size_t m = vertices.size();
  // A point repeated further apart (a polygon that touches itself) has no
  // single outline: its fan's pieces are kept where they have area.
  bool repeats = false;
  for (size_t a = 0; a < m && !repeats; ++a)
    for (size_t b = a + 1; b < m && !repeats; ++b)
      repeats = scene.positions[vertices[a]] == scene.positions[vertices[b]];

  if (m == 3) {
    addPiece(scene, vertices, uvs, normals, {0, 1, 2}, material, object);
    return;
  }
  if (m > 4 || repeats) {
    for (size_t k = 1; k + 1 < m; ++k)
      addPiece(scene, vertices, uvs, normals, {0, static_cast<int>(k), static_cast<int>(k + 1)}, material, object);
    return;
  }

  // A quad stays a quad (the radiosity mesher subdivides quads as quads) only
  // when it is planar and convex. Otherwise the fan from v0 that Scene splits it
  // into would not be the surface: a reflex corner must be an end of the split
  // diagonal, and a non-planar quad (the Cornell left wall is 3.2 mm off) has no
  // single normal.
  Vec3 normal = newellNormal(scene, vertices);
  const Vec3 *p[4];
  for (int k = 0; k < 4; ++k) p[k] = &scene.positions[vertices[k]];
  double size = std::max(length(*p[2] - *p[0]), length(*p[3] - *p[1]));
  Vec3 unitNormal = normalize(normal);
  Vec3 centroid = (*p[0] + *p[1] + *p[2] + *p[3]) * 0.25;
  bool planar = true;
  for (int k = 0; k < 4; ++k) planar = planar && std::abs(dot(*p[k] - centroid, unitNormal)) <= 1e-7 * size;
  int reflexCorner = -1;
  for (int k = 0; k < 4; ++k) {
    const Vec3 &before = *p[(k + 3) % 4], &at = *p[k], &after = *p[(k + 1) % 4];
    if (dot(cross(at - before, after - at), normal) < 0) reflexCorner = k;
  }
  if (planar && reflexCorner < 0) {
    addPiece(scene, vertices, uvs, normals, {0, 1, 2, 3}, material, object);
  } else if (reflexCorner == 1 || reflexCorner == 3) {
    addPiece(scene, vertices, uvs, normals, {1, 2, 3}, material, object);
    addPiece(scene, vertices, uvs, normals, {1, 3, 0}, material, object);
  } else {
    addPiece(scene, vertices, uvs, normals, {0, 1, 2}, material, object);
    addPiece(scene, vertices, uvs, normals, {0, 2, 3}, material, object);
  }
}

void addUvSphere(Scene &scene, const Vec3 &center, double radius, int segments, const Transform &toWorld,
                 uint32_t material, uint32_t object) {
  const int slices = std::max(3, segments);
  const int stacks = std::max(2, segments / 2);
  const uint32_t firstPosition = static_cast<uint32_t>(scene.positions.size());
  const int32_t firstNormal = static_cast<int32_t>(scene.normals.size());
  const int32_t firstUv = static_cast<int32_t>(scene.uvs.size() / 2);
  // (stacks + 1) rows × (slices + 1) columns: the seam column and the poles are
  // repeated so that every vertex has one uv.
  for (int i = 0; i <= stacks; ++i) {
    double theta = kPi * i / stacks;
    for (int j = 0; j <= slices; ++j) {
      double phi = 2.0 * kPi * (j % slices) / slices;
      Vec3 direction{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
      if (i == 0 || i == stacks) direction = Vec3{0, std::cos(theta), 0};
      scene.positions.push_back(toWorld.point(center + direction * radius));
      scene.normals.push_back(toWorld.normal(direction));
      scene.uvs.push_back(static_cast<double>(j) / slices);
      scene.uvs.push_back(1.0 - static_cast<double>(i) / stacks);
    }
  }
  const bool flip = toWorld.determinant() < 0;
  auto at = [&](int i, int j) { return i * (slices + 1) + j; };
  for (int i = 0; i < stacks; ++i) {
    for (int j = 0; j < slices; ++j) {
      // a (i, j) → d (i, j+1) → c (i+1, j+1) → b (i+1, j) runs counter-clockwise
      // seen from outside (θ grows downwards, φ from +x towards +z).
      // The pole rows are triangles: their pole corner would be repeated.
      std::vector<int> ring;
      if (i == 0)
        ring = {at(0, j), at(1, j + 1), at(1, j)};
      else if (i + 1 == stacks)
        ring = {at(i, j), at(i, j + 1), at(i + 1, j)};
      else
        ring = {at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)};
      std::vector<uint32_t> vertices;
      std::vector<int32_t> uvs, normals;
      for (int k : ring) {
        vertices.push_back(firstPosition + static_cast<uint32_t>(k));
        uvs.push_back(firstUv + k);
        normals.push_back(firstNormal + k);
      }
      addPolygon(scene, vertices, uvs, normals, material, object, flip);
    }
  }
}

void dropRepeatedFaces(Scene &scene) {
  // Two faces with the same corner key are the same surface facing the same
  // way. (The reverse order is the other side of a thin sheet, which is a
  // surface of its own and stays: Scene::addBackFaces pairs the two.)
  std::map<std::vector<std::array<double, 3>>, uint32_t> firstWithKey;
  std::vector<int64_t> newIndex(scene.faces.size(), -1);
  std::vector<Face> kept;
  size_t repeated = 0;
  std::string example;
  for (size_t i = 0; i < scene.faces.size(); ++i) {
    auto [at, inserted] = firstWithKey.emplace(scene.cornerKey(scene.faces[i]), uint32_t(kept.size()));
    if (!inserted) {
      const Face &face = scene.faces[i];
      std::array<Vec3, 4> corners;
      for (int k = 0; k < face.vertexCount; ++k) corners[size_t(k)] = scene.positions[face.vertices[k]];
      const uint32_t firstObject = kept[at->second].object;
      scene.loadChanges.record(
          LoadChangeKind::RepeatedFace, face.object,
          finiteCentroid(std::span<const Vec3>(corners.data(), size_t(face.vertexCount))),
          "the same corners as a face of '" + scene.objects[firstObject].name + "', facing the same way");
      if (repeated++ == 0) {
        const Face &first = kept[at->second];
        example = "object '" + scene.objects[scene.faces[i].object].name + "' repeats a face of '" +
                  scene.objects[first.object].name + "'";
      }
      continue;
    }
    newIndex[i] = int64_t(kept.size());
    kept.push_back(scene.faces[i]);
  }
  if (repeated == 0) return;
  std::vector<Triangle> triangles;
  for (Triangle t : scene.triangles)
    if (newIndex[t.face] >= 0) t.face = uint32_t(newIndex[t.face]), triangles.push_back(t);
  scene.faces = std::move(kept);
  scene.triangles = std::move(triangles);
  // Two copies of one surface fight over every ray that reaches them (each
  // shadows the other at distance 0), and a solver never settles their
  // radiosities; one copy is the surface the model means.
  scene.warnings.push_back("dropped " + std::to_string(repeated) + " face" + (repeated == 1 ? "" : "s") +
                           " that repeat another face exactly (same corners, facing the same way; " + example + ")");
}

CameraSettings frameBounds(const Scene &scene) {
  CameraSettings camera;
  if (scene.positions.empty()) return camera;
  Vec3 lo = scene.positions.front(), hi = lo;
  for (const Vec3 &p : scene.positions)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  Vec3 center = (lo + hi) * 0.5;
  double radius = 0.5 * length(hi - lo);
  if (!(radius > 0)) radius = 1.0;
  camera.verticalFovDegrees = 40.0;
  // The bounding sphere just fits the vertical field of view at this distance;
  // 5% margin so the silhouette does not touch the frame.
  double distance = 1.05 * radius / std::sin(0.5 * camera.verticalFovDegrees * kPi / 180.0);
  camera.eye = center + Vec3{0, 0, distance};
  camera.target = center;
  camera.up = Vec3{0, 1, 0};
  return camera;
}

}  // namespace radiant::detail
