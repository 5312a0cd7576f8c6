// glTF 2.0 scenes and models (.gltf with its .bin and images, or .glb).
//
// What is read (docs/scene-format.md, "glTF scenes", has the table):
//   the default scene's node trees (scene 0 when none is named; every root
//   node when the file has no scenes), each node's matrix or TRS transform,
//   every mesh a node holds (instanced once per node), triangles (mode 4) and
//   triangle strips and fans (5, 6) with POSITION, NORMAL (shading normals)
//   and TEXCOORD_0 (v flipped: glTF's v runs down the image, Radiant's up);
//   materials: extras.radiant (written by radiant export) exactly as Radiant
//   defines the material, otherwise the metallic-roughness approximation —
//   baseColorFactor × baseColorTexture → diffuse reflectance ρ (eq. 9.11's
//   texture), emissiveFactor × KHR_materials_emissive_strength → emitted
//   radiance in W·sr⁻¹·m⁻² (glTF gives emission no absolute unit: Radiant
//   reads it as radiance), metallic 1 with roughness 0 → a mirror,
//   KHR_materials_transmission → glass with KHR_materials_ior; the first
//   perspective camera (lowest node index) of the scene.
//
// The JSON is read through JsonNode, so that every refusal names the file and
// the JSON path inside it (`model.gltf: at /accessors/3: …`). tinygltf reads
// only what is not JSON: the buffers (the GLB's BIN chunk, data: URIs,
// external .bin files) and the bytes of the images, which Texture::decode
// decodes. tinygltf 2.7 reads an image's buffer view without checking it
// against its buffer, so every buffer view is checked against its buffer's
// byteLength before tinygltf runs; every accessor a primitive uses is checked
// against its buffer view before a byte of it is read, and the triangles of
// all the instances are counted against kMaxGltfTriangles before any is
// added, so a file that lies about its sizes is refused before it can make
// the loader read out of bounds or allocate gigabytes.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "scene/gltf_file.h"
#include "scene/load_detail.h"
#include "scene/load_scene.h"

namespace radiant {

namespace {

using namespace gltf;

/// The most triangles the instances of one glTF file may add (about 3 GB of
/// faces, triangles and vertices), and three times as many vertices: a small
/// file that instances a large mesh under thousands of nodes is refused
/// before it allocates.
constexpr uint64_t kMaxGltfTriangles = uint64_t(1) << 24;

/// The node's local transform: its matrix (column-major), or T · R · S.
Transform nodeTransform(const JsonNode &node) {
  Transform t;
  if (node.has("matrix")) {
    if (node.has("translation") || node.has("rotation") || node.has("scale"))
      node.child("matrix").fail("a node has a matrix or translation/rotation/scale, not both");
    std::vector<JsonNode> values = node.child("matrix").asArray(16, 16);
    double m[16];
    for (int k = 0; k < 16; ++k) m[k] = values[size_t(k)].asNumber();
    // Column-major: element (row r, column c) is m[4c + r]; the last row must be (0, 0, 0, 1).
    if (m[3] != 0 || m[7] != 0 || m[11] != 0 || m[15] != 1)
      node.child("matrix").fail("the matrix's last row is not (0, 0, 0, 1): a projective transform");
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) t.m[r][c] = m[4 * c + r];
    return t;
  }
  if (node.has("scale")) t = Transform::scale(node.child("scale").asVec3());
  if (node.has("rotation")) {
    JsonNode rotationNode = node.child("rotation");
    std::vector<JsonNode> q = rotationNode.asArray(4, 4);
    double x = q[0].asNumber(), y = q[1].asNumber(), z = q[2].asNumber(), w = q[3].asNumber();
    const double norm = std::sqrt(x * x + y * y + z * z + w * w);
    if (!(norm > 0)) rotationNode.fail("the rotation quaternion is zero");
    x /= norm, y /= norm, z /= norm, w /= norm;
    Transform r;
    r.m[0][0] = 1 - 2 * (y * y + z * z), r.m[0][1] = 2 * (x * y - z * w), r.m[0][2] = 2 * (x * z + y * w);
    r.m[1][0] = 2 * (x * y + z * w), r.m[1][1] = 1 - 2 * (x * x + z * z), r.m[1][2] = 2 * (y * z - x * w);
    r.m[2][0] = 2 * (x * z - y * w), r.m[2][1] = 2 * (y * z + x * w), r.m[2][2] = 1 - 2 * (x * x + y * y);
    t = r * t;
  }
  if (node.has("translation")) t = Transform::translate(node.child("translation").asVec3()) * t;
  return t;
}

/// One mesh placed by one node.
struct Instance {
  size_t node = 0, mesh = 0;
  Transform toWorld;  ///< node to scene, the entry's transform and units included
};

/// Reading one glTF file's scene into a Radiant scene.
class GltfReader {
 public:
  GltfReader(Scene &scene, const std::string &path, const InputLocation &fileFrom)
      : scene_(scene), file_(path, fileFrom, scene.warnings) {}

  /// Appends the scene's meshes; returns the first perspective camera's view.
  detail::GltfView append(const Transform &toWorld, const std::string &objectName, int defaultMaterial,
                          size_t overridableMaterials) {
    objectName_ = objectName;
    defaultMaterial_ = defaultMaterial;
    overridableMaterials_ = overridableMaterials;
    collectInstances(toWorld);
    countTriangles();
    for (const Instance &instance : instances_) appendInstance(instance);
    return view_;
  }

 private:
  JsonNode entry(const std::string &key, const JsonNode &reference) const { return file_.entry(key, reference); }
  std::vector<JsonNode> list(const std::string &key) const { return file_.list(key); }
  InputLocation at(const std::string &jsonPath) const { return file_.at(jsonPath); }
  AccessorView accessor(const JsonNode &reference, const std::vector<int> &components,
                        const std::vector<int> &componentTypes, bool allowNormalized = true) const {
    return file_.accessor(reference, components, componentTypes, allowNormalized);
  }

  /// The scene's node trees, walked without recursion (a file may nest
  /// thousands of nodes): every node with a mesh becomes an instance, and
  /// the camera of the lowest-numbered node that has one becomes the view.
  void collectInstances(const Transform &toWorld) {
    const std::vector<JsonNode> nodes = list("nodes");
    std::vector<JsonNode> roots;
    if (file_.root().has("scenes") && !list("scenes").empty()) {
      JsonNode sceneNode = file_.root().has("scene") ? entry("scenes", file_.root().child("scene")) : list("scenes")[0];
      if (sceneNode.has("nodes")) roots = sceneNode.child("nodes").asArray();
    } else {
      // No scenes: every node that is no other node's child is a root.
      std::vector<bool> isChild(nodes.size());
      for (const JsonNode &node : nodes)
        if (node.has("children"))
          for (const JsonNode &child : node.child("children").asArray()) {
            entry("nodes", child);
            isChild[size_t(child.asInteger(0, INT32_MAX))] = true;
          }
      for (size_t i = 0; i < nodes.size(); ++i)
        if (!isChild[i]) rootIndices_.push_back(i);
    }
    struct Pending {
      size_t node;
      Transform parent;
      std::string reference;  ///< where the index came from, for "reached twice"
    };
    std::vector<Pending> stack;
    for (const JsonNode &reference : roots) {
      entry("nodes", reference);
      stack.push_back({size_t(reference.asInteger(0, INT32_MAX)), toWorld, reference.path()});
    }
    for (size_t i : rootIndices_) stack.push_back({i, toWorld, "/nodes/" + std::to_string(i)});
    std::reverse(stack.begin(), stack.end());  // depth-first in file order
    std::vector<bool> seen(nodes.size());
    int cameraNode = -1;
    while (!stack.empty()) {
      Pending pending = stack.back();
      stack.pop_back();
      const JsonNode &node = nodes[pending.node];
      if (seen[pending.node])
        throw InputError(
            at(pending.reference),
            fmt::format("node {} is reached a second time: glTF nodes form trees (one parent each)", pending.node));
      seen[pending.node] = true;
      node.expectObject();
      const Transform world = pending.parent * nodeTransform(node);
      if (node.has("mesh")) {
        entry("meshes", node.child("mesh"));
        instances_.push_back({pending.node, size_t(node.child("mesh").asInteger(0, INT32_MAX)), world});
      }
      if (node.has("camera") && (cameraNode < 0 || int(pending.node) < cameraNode)) {
        JsonNode camera = entry("cameras", node.child("camera"));
        const std::string type = camera.child("type").asString();
        if (type == "perspective") {
          cameraNode = int(pending.node);
          setView(camera, world);
        } else if (!orthographicWarned_) {
          orthographicWarned_ = true;
          scene_.warnings.push_back(file_.path() + ": the " + type + " camera at " + camera.path() +
                                    " is not read; Radiant's camera is a pinhole (perspective)");
        }
      }
      if (node.has("children")) {
        std::vector<JsonNode> children = node.child("children").asArray();
        for (auto child = children.rbegin(); child != children.rend(); ++child) {
          entry("nodes", *child);
          stack.push_back({size_t(child->asInteger(0, INT32_MAX)), world, child->path()});
        }
      }
    }
  }

  void setView(const JsonNode &camera, const Transform &world) {
    JsonNode perspective = camera.child("perspective");
    const double yfov = perspective.child("yfov").asNumber();
    if (!(yfov > 0 && yfov < kPi)) perspective.child("yfov").fail("yfov must lie in (0, π) radians");
    view_.hasCamera = true;
    view_.camera.eye = world.point(Vec3{0, 0, 0});
    const Vec3 forward = world.vector(Vec3{0, 0, -1}), up = world.vector(Vec3{0, 1, 0});
    if (!(length(forward) > 0) || !(length(up) > 0) || !(length(cross(forward, up)) > 0))
      camera.fail("the camera's node transform flattens its view (a zero scale?)");
    view_.camera.target = view_.camera.eye + normalize(forward);
    view_.camera.up = normalize(up);
    view_.camera.verticalFovDegrees = yfov * 180 / kPi;
    view_.aspectRatio = 0;
    if (perspective.has("aspectRatio")) {
      view_.aspectRatio = perspective.child("aspectRatio").asNumber();
      if (!(view_.aspectRatio > 0)) perspective.child("aspectRatio").fail("aspectRatio must be > 0");
    }
    view_.cameraFrom = camera.location();
  }

  /// The instances' triangles and vertices, counted before any is added.
  void countTriangles() {
    struct Size {
      uint64_t triangles = 0, vertices = 0;
    };
    Size total;
    std::map<size_t, Size> perMesh;
    for (const Instance &instance : instances_) {
      auto [it, inserted] = perMesh.try_emplace(instance.mesh);
      if (inserted) {
        JsonNode mesh = file_.root().child("meshes").element(instance.mesh);
        for (const JsonNode &primitive : mesh.child("primitives").asArray()) {
          const int mode = primitiveMode(primitive);
          const JsonNode positions = entry("accessors", primitive.child("attributes").child("POSITION"));
          const uint64_t vertices = uint64_t(positions.child("count").asInteger(0, INT64_MAX));
          const uint64_t count =
              primitive.has("indices")
                  ? uint64_t(entry("accessors", primitive.child("indices")).child("count").asInteger(0, INT64_MAX))
                  : vertices;
          // Saturating: a lying count near 2⁶³ must not wrap the sums.
          const uint64_t triangles = mode == 4 ? count / 3 : (count >= 3 ? count - 2 : 0);
          it->second.triangles = std::min(it->second.triangles + triangles, uint64_t(1) << 63);
          it->second.vertices = std::min(it->second.vertices + vertices, uint64_t(1) << 63);
        }
      }
      total.triangles += it->second.triangles;
      total.vertices += it->second.vertices;
      if (total.triangles > kMaxGltfTriangles || total.vertices > 3 * kMaxGltfTriangles)
        throw InputError(at("/nodes/" + std::to_string(instance.node)),
                         fmt::format("the scene's meshes, placed by its nodes up to this one, have {} triangles and "
                                     "{} vertices; Radiant reads at most {} and {}",
                                     total.triangles, total.vertices, kMaxGltfTriangles, 3 * kMaxGltfTriangles));
    }
  }

  static int primitiveMode(const JsonNode &primitive) {
    const int64_t mode = primitive.integer("mode", 4, 0, 6);
    static const char *kNames[] = {"points", "lines", "a line loop", "a line strip"};
    if (mode < 4)
      primitive.child("mode").fail(
          fmt::format("mode {} ({}): Radiant renders surfaces, and reads triangles (4), "
                      "triangle strips (5) and triangle fans (6)",
                      mode, kNames[mode]));
    return int(mode);
  }

  std::string objectNameFor(const Instance &instance) {
    JsonNode node = file_.root().child("nodes").element(instance.node);
    JsonNode mesh = file_.root().child("meshes").element(instance.mesh);
    std::string name = node.string("name", "");
    if (name.empty()) name = mesh.string("name", "");
    if (name.empty()) name = "node-" + std::to_string(instance.node);
    name = objectName_ + "/" + name;
    if (!objectNames_.insert(name).second) {
      name += "#" + std::to_string(instance.node);
      objectNames_.insert(name);
    }
    return name;
  }

  void appendInstance(const Instance &instance) {
    const uint32_t object = uint32_t(scene_.objects.size());
    scene_.objects.push_back(SceneObject{
        objectNameFor(instance), fmt::format("{} (node {}, mesh {})", file_.path(), instance.node, instance.mesh)});
    const bool flip = instance.toWorld.determinant() < 0;
    JsonNode mesh = file_.root().child("meshes").element(instance.mesh);
    for (const JsonNode &primitive : mesh.child("primitives").asArray())
      appendPrimitive(primitive, instance, object, flip);
  }

  void appendPrimitive(const JsonNode &primitive, const Instance &instance, uint32_t object, bool flip) {
    const int mode = primitiveMode(primitive);
    JsonNode attributes = primitive.child("attributes");
    const std::vector<int> kFloatAndQuantised = {kComponentFloat, kComponentByte, kComponentUnsignedByte,
                                                 kComponentShort, kComponentUnsignedShort};
    const AccessorView positions = accessor(attributes.child("POSITION"), {3}, kFloatAndQuantised);
    const uint32_t material = materialFor(primitive);

    const uint32_t firstPosition = uint32_t(scene_.positions.size());
    for (size_t i = 0; i < positions.count; ++i) {
      const Vec3 p = instance.toWorld.point(Vec3{positions.get(i, 0), positions.get(i, 1), positions.get(i, 2)});
      if (!withinCoordinateRange(p))
        throw InputError(at(positions.path),
                         fmt::format("element {} lies at ({:g}, {:g}, {:g}) m in the scene (node {}), more than {:g} "
                                     "m from the origin or not finite; the ray tracer works in single precision",
                                     i, p.x, p.y, p.z, instance.node, kMaxCoordinateMetres));
      scene_.positions.push_back(p);
    }
    // Shading normals: a zero or non-finite one leaves its triangles without.
    int32_t firstNormal = -1;
    std::vector<bool> normalOk;
    if (attributes.has("NORMAL")) {
      const AccessorView normals =
          accessor(attributes.child("NORMAL"), {3}, {kComponentFloat, kComponentByte, kComponentShort});
      checkSameCount(normals, positions, attributes.child("NORMAL"));
      firstNormal = int32_t(scene_.normals.size());
      for (size_t i = 0; i < normals.count; ++i) {
        const Vec3 n{normals.get(i, 0), normals.get(i, 1), normals.get(i, 2)};
        const bool ok = std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z) && length(n) > 0;
        normalOk.push_back(ok);
        scene_.normals.push_back(ok ? instance.toWorld.normal(n) : Vec3{0, 0, 1});
      }
    }
    int32_t firstUv = -1;
    if (attributes.has("TEXCOORD_0")) {
      const AccessorView uvs = accessor(attributes.child("TEXCOORD_0"), {2}, kFloatAndQuantised);
      checkSameCount(uvs, positions, attributes.child("TEXCOORD_0"));
      firstUv = int32_t(scene_.uvs.size() / 2);
      for (size_t i = 0; i < uvs.count; ++i) {
        const double u = uvs.get(i, 0), v = uvs.get(i, 1);
        if (!std::isfinite(u) || !std::isfinite(v))
          throw InputError(at(uvs.path), fmt::format("element {} is not finite", i));
        scene_.uvs.push_back(u);
        scene_.uvs.push_back(1 - v);  // glTF's v runs down the image; Radiant's (the OBJ convention) up
      }
    }

    // The primitive's vertex indices, in the order its mode lists them.
    std::vector<uint32_t> indices;
    if (primitive.has("indices")) {
      const AccessorView view =
          accessor(primitive.child("indices"), {1},
                   {kComponentUnsignedByte, kComponentUnsignedShort, kComponentUnsignedInt}, false);
      indices.reserve(view.count);
      for (size_t i = 0; i < view.count; ++i) {
        const double index = view.get(i, 0);
        if (index >= double(positions.count))
          throw InputError(at(view.path), fmt::format("index {} (element {}) is out of range: the primitive has {} "
                                                      "vertices",
                                                      index, i, positions.count));
        indices.push_back(uint32_t(index));
      }
    } else {
      indices.resize(positions.count);
      for (size_t i = 0; i < positions.count; ++i) indices[i] = uint32_t(i);
    }
    auto addTriangle = [&](uint32_t a, uint32_t b, uint32_t c) {
      const uint32_t corner[3] = {a, b, c};
      const bool withNormals = firstNormal >= 0 && normalOk[a] && normalOk[b] && normalOk[c];
      std::vector<uint32_t> vertices;
      std::vector<int32_t> uvs, normals;
      for (uint32_t k : corner) {
        vertices.push_back(firstPosition + k);
        uvs.push_back(firstUv >= 0 ? firstUv + int32_t(k) : -1);
        normals.push_back(withNormals ? firstNormal + int32_t(k) : -1);
      }
      detail::addPolygon(scene_, vertices, uvs, normals, material, object, flip);
    };
    const size_t n = indices.size();
    if (mode == 4) {
      if (n % 3 != 0)
        scene_.warnings.push_back(
            fmt::format("{}: {}: {} indices are not a whole number of triangles; the last {} "
                        "are left out",
                        file_.path(), primitive.path(), n, n % 3));
      for (size_t i = 0; i + 2 < n; i += 3) addTriangle(indices[i], indices[i + 1], indices[i + 2]);
    } else if (mode == 5) {
      // Strips alternate their winding (glTF 2.0 §3.7.2.1): triangle i is (i, i+1, i+2) for even i, (i+1, i, i+2) odd.
      for (size_t i = 0; i + 2 < n; ++i)
        if (i % 2 == 0)
          addTriangle(indices[i], indices[i + 1], indices[i + 2]);
        else
          addTriangle(indices[i + 1], indices[i], indices[i + 2]);
    } else {
      for (size_t i = 1; i + 1 < n; ++i) addTriangle(indices[i], indices[i + 1], indices[0]);
    }
  }

  void checkSameCount(const AccessorView &attribute, const AccessorView &positions, const JsonNode &reference) const {
    if (attribute.count != positions.count)
      reference.fail(
          fmt::format("{} has {} elements and POSITION ({}) {}; a primitive's attributes have one "
                      "element per vertex",
                      attribute.path, attribute.count, positions.path, positions.count));
  }

  uint32_t materialFor(const JsonNode &primitive) {
    if (!primitive.has("material"))
      return defaultMaterial_ >= 0 ? uint32_t(defaultMaterial_) : detail::defaultMaterialIndex(scene_);
    JsonNode material = entry("materials", primitive.child("material"));
    const size_t index = size_t(primitive.child("material").asInteger(0, INT32_MAX));
    if (auto it = materials_.find(index); it != materials_.end()) return it->second;
    // A material of the same name in the JSON scene wins, as over an MTL material.
    const std::string base = material.string("name", "");
    const std::string name = base.empty() ? "material-" + std::to_string(index) : base;
    const int existing = materialNames_.find(name);
    if (existing >= 0 && size_t(existing) < overridableMaterials_) return materials_[index] = uint32_t(existing);
    Material converted = convertMaterial(file_, material, scene_, textures_);
    converted.name = name;
    // Another file's material of the same name (Blender names every first material "Material") stays its own.
    if (existing >= 0) converted.name = objectName_ + "/" + name;
    while (materialNames_.find(converted.name) >= 0) converted.name += "#" + std::to_string(index);
    scene_.materials.push_back(std::move(converted));
    return materials_[index] = uint32_t(scene_.materials.size() - 1);
  }

  Scene &scene_;
  GltfFile file_;

  std::string objectName_;
  int defaultMaterial_ = -1;
  size_t overridableMaterials_ = 0;
  std::vector<Instance> instances_;
  std::vector<size_t> rootIndices_;
  detail::GltfView view_;
  std::map<size_t, uint32_t> materials_;  ///< glTF material → scene material
  detail::MaterialNames materialNames_{scene_.materials};
  TextureCache textures_;
  std::set<std::string> objectNames_;
  bool orthographicWarned_ = false;
};

}  // namespace

detail::GltfView detail::appendGltf(Scene &scene, const std::string &path, const Transform &toWorld,
                                    const std::string &objectName, int defaultMaterial, size_t overridableMaterials,
                                    const InputLocation &fileFrom) {
  GltfReader reader(scene, path, fileFrom);
  return reader.append(toWorld, objectName, defaultMaterial, overridableMaterials);
}

}  // namespace radiant
