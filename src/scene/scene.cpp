#include "scene/scene.h"

#include <array>
#include <map>

namespace radiant {

double Scene::faceArea(const Face &f) const {
  double area = 0;
  for (int k = 1; k + 1 < f.vertexCount; ++k)
    area += 0.5 * length(cross(positions[f.vertices[k]] - positions[f.vertices[0]],
                               positions[f.vertices[k + 1]] - positions[f.vertices[0]]));
  return area;
}

Vec3 Scene::faceNormal(const Face &f) const {
  Vec3 n;
  for (int k = 0; k < f.vertexCount; ++k) {
    const Vec3 &a = positions[f.vertices[k]];
    const Vec3 &b = positions[f.vertices[(k + 1) % f.vertexCount]];
    n += Vec3{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
  }
  return normalize(n);
}

bool Scene::addFace(const Face &face) {
  // Split into a fan; a triangle whose area is tiny against its edges is
  // dropped (it has no well-defined normal and would only add NaNs).
  std::vector<Triangle> kept;
  for (int k = 1; k + 1 < face.vertexCount; ++k) {
    int i0 = 0, i1 = k, i2 = k + 1;
    const Vec3 &a = positions[face.vertices[i0]], &b = positions[face.vertices[i1]], &c = positions[face.vertices[i2]];
    if (!isFinite(a) || !isFinite(b) || !isFinite(c)) continue;
    double twiceArea = length(cross(b - a, c - a));
    double longest = std::max({length(b - a), length(c - b), length(a - c)});
    if (!(twiceArea > 1e-12 * longest * longest) || longest == 0) continue;
    Triangle t{};
    for (int j = 0; j < 3; ++j) {
      int src = j == 0 ? i0 : (j == 1 ? i1 : i2);
      t.v[j] = face.vertices[src];
      t.uv[j] = face.uvs[src];
      t.n[j] = face.normals[src];
    }
    t.face = static_cast<uint32_t>(faces.size());
    t.material = face.material;
    kept.push_back(t);
  }
  std::array<Vec3, 4> corners;
  for (int k = 0; k < face.vertexCount; ++k) corners[size_t(k)] = positions[face.vertices[k]];
  const std::span<const Vec3> cornerSpan(corners.data(), size_t(face.vertexCount));
  if (kept.empty()) {
    bool finite = true;
    for (const Vec3 &p : cornerSpan) finite = finite && isFinite(p);
    dropDegenerateFace(cornerSpan, face.object, finite ? "zero area" : "a corner is not finite");
    return false;
  }
  if (face.vertexCount == 4 && kept.size() == 1) {
    // Three corners of the quad on one line: its area is one triangle, and a
    // quad with a straight corner would give the mesher zero-area elements.
    loadChanges.record(LoadChangeKind::CollinearQuad, face.object, finiteCentroid(cornerSpan),
                       "three of its corners on one line");
    Face triangle = face;
    triangle.vertexCount = 3;
    for (int j = 0; j < 3; ++j) {
      triangle.vertices[j] = kept[0].v[j];
      triangle.uvs[j] = kept[0].uv[j];
      triangle.normals[j] = kept[0].n[j];
    }
    faces.push_back(triangle);
    triangles.push_back(kept[0]);
    return true;
  }
  faces.push_back(face);
  triangles.insert(triangles.end(), kept.begin(), kept.end());
  return true;
}

void Scene::dropDegenerateFace(std::span<const Vec3> corners, uint32_t object, std::string reason) {
  ++droppedDegenerateFaces;
  loadChanges.record(LoadChangeKind::DegenerateFace, object, finiteCentroid(corners), std::move(reason));
}

std::vector<std::array<double, 3>> Scene::cornerKey(const Face &f, bool reversed) const {
  std::vector<std::array<double, 3>> key;
  for (int k = 0; k < f.vertexCount; ++k) {
    const Vec3 &p = positions[f.vertices[reversed ? (f.vertexCount - k) % f.vertexCount : k]];
    key.push_back({p.x, p.y, p.z});
  }
  std::rotate(key.begin(), std::min_element(key.begin(), key.end()), key.end());
  return key;
}

void Scene::addBackFaces() {
  // Faces already back to back (the same corners in the reverse cyclic order,
  // as a modeller makes a sheet with two sides) are paired as they are.
  std::map<std::vector<std::array<double, 3>>, uint32_t> unpaired;
  for (uint32_t f = 0; f < faces.size(); ++f) {
    if (faces[f].twin >= 0) continue;
    if (auto it = unpaired.find(cornerKey(faces[f], true)); it != unpaired.end()) {
      std::array<Vec3, 4> corners;
      for (int k = 0; k < faces[f].vertexCount; ++k) corners[size_t(k)] = positions[faces[f].vertices[k]];
      const uint32_t first = faces[it->second].object, second = faces[f].object;
      loadChanges.record(LoadChangeKind::BackToBack, second,
                         finiteCentroid(std::span<const Vec3>(corners.data(), size_t(faces[f].vertexCount))),
                         first == second || first >= objects.size()
                             ? std::string("the two sides of one surface")
                             : "the back of a face of '" + objects[first].name + "'");
      faces[it->second].twin = int32_t(f);
      faces[f].twin = int32_t(it->second);
      faces[f].back = true;
      unpaired.erase(it);
    } else {
      unpaired.emplace(cornerKey(faces[f]), f);
    }
  }
  const size_t count = faces.size();
  for (size_t f = 0; f < count; ++f) {
    if (faces[f].twin >= 0 || !materials[faces[f].material].twoSided) continue;
    // The same corners counter-clockwise seen from behind: 0, n−1, …, 1.
    const Face &front = faces[f];
    Face back = front;
    for (int k = 1; k < front.vertexCount; ++k) {
      const int from = front.vertexCount - k;
      back.vertices[k] = front.vertices[from];
      back.uvs[k] = front.uvs[from];
      back.normals[k] = front.normals[from];
    }
    back.twin = static_cast<int32_t>(f);
    back.back = true;
    const int32_t index = static_cast<int32_t>(faces.size());
    if (addFace(back)) faces[f].twin = index;
  }
}

const char *materialKindName(MaterialKind kind) {
  switch (kind) {
    case MaterialKind::Lambertian:
      return "lambertian";
    case MaterialKind::Mirror:
      return "mirror";
    case MaterialKind::Dielectric:
      return "dielectric";
    case MaterialKind::Glossy:
      return "glossy";
  }
  return "?";
}

}  // namespace radiant
