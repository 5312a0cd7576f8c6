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
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "scene/json_reader.h"
#include "scene/load_detail.h"
#include "scene/load_scene.h"

namespace radiant {

namespace fs = std::filesystem;

namespace {

/// The most triangles the instances of one glTF file may add (about 3 GB of
/// faces, triangles and vertices): a small file that instances a large mesh
/// under thousands of nodes is refused before it allocates.
constexpr uint64_t kMaxGltfTriangles = uint64_t(1) << 24;

constexpr int kComponentByte = 5120, kComponentUnsignedByte = 5121, kComponentShort = 5122,
              kComponentUnsignedShort = 5123, kComponentUnsignedInt = 5125, kComponentFloat = 5126;

size_t componentSize(int type) {
  switch (type) {
    case kComponentByte:
    case kComponentUnsignedByte:
      return 1;
    case kComponentShort:
    case kComponentUnsignedShort:
      return 2;
    case kComponentUnsignedInt:
    case kComponentFloat:
      return 4;
    default:
      return 0;
  }
}

const char *componentName(int type) {
  switch (type) {
    case kComponentByte:
      return "BYTE";
    case kComponentUnsignedByte:
      return "UNSIGNED_BYTE";
    case kComponentShort:
      return "SHORT";
    case kComponentUnsignedShort:
      return "UNSIGNED_SHORT";
    case kComponentUnsignedInt:
      return "UNSIGNED_INT";
    case kComponentFloat:
      return "FLOAT";
    default:
      return "?";
  }
}

/// The elements of an accessor, checked to lie inside their buffer view and buffer.
struct AccessorView {
  std::string path;  ///< "/accessors/N"
  const unsigned char *data = nullptr;
  size_t count = 0, stride = 0;
  int componentType = 0, components = 0;
  bool normalized = false;

  /// Component `c` of element `i` as a number; normalized integers map to
  /// [0, 1] or [−1, 1] (glTF 2.0 §3.11), other integers are their value.
  double get(size_t i, int c) const {
    const unsigned char *at = data + i * stride + size_t(c) * componentSize(componentType);
    auto read = [at]<typename T>(T) {
      T value;
      std::memcpy(&value, at, sizeof value);  // glTF is little-endian, as are the hosts Radiant runs on
      return value;
    };
    switch (componentType) {
      case kComponentByte: {
        const double v = read(int8_t{});
        return normalized ? std::max(v / 127.0, -1.0) : v;
      }
      case kComponentUnsignedByte: {
        const double v = read(uint8_t{});
        return normalized ? v / 255.0 : v;
      }
      case kComponentShort: {
        const double v = read(int16_t{});
        return normalized ? std::max(v / 32767.0, -1.0) : v;
      }
      case kComponentUnsignedShort: {
        const double v = read(uint16_t{});
        return normalized ? v / 65535.0 : v;
      }
      case kComponentUnsignedInt:
        return read(uint32_t{});
      default:
        return read(float{});
    }
  }
};

std::string typeName(int components) {
  return components == 1 ? "SCALAR" : "VEC" + std::to_string(components);
}

int componentsOf(const std::string &type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4") return 4;
  if (type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

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

/// The GLB container (glTF 2.0 §4.4): a 12-byte header, a JSON chunk, an optional BIN chunk.
std::string glbJson(const std::vector<unsigned char> &bytes, const InputLocation &where) {
  auto word = [&](size_t at) {
    uint32_t value;
    std::memcpy(&value, bytes.data() + at, 4);
    return value;
  };
  if (bytes.size() < 20) throw InputError(where, fmt::format("a GLB file of {} bytes is truncated", bytes.size()));
  if (word(4) != 2) throw InputError(where, fmt::format("GLB version {}; Radiant reads glTF 2.0", word(4)));
  if (word(8) > bytes.size())
    throw InputError(where,
                     fmt::format("the GLB header says {} bytes, the file has {} (truncated?)", word(8), bytes.size()));
  const uint64_t jsonLength = word(12);
  if (word(16) != 0x4E4F534A) throw InputError(where, "the GLB's first chunk is not JSON");
  if (20 + jsonLength > word(8))
    throw InputError(
        where, fmt::format("the GLB's JSON chunk of {} bytes runs past the {} bytes of the file", jsonLength, word(8)));
  return std::string(reinterpret_cast<const char *>(bytes.data()) + 20, size_t(jsonLength));
}

/// tinygltf's image callback: keeps the encoded bytes; Texture::decode decodes
/// the ones a material uses, with the texture module's checks.
bool keepImageBytes(tinygltf::Image *image, const int, std::string *, std::string *, int, int,
                    const unsigned char *bytes, int size, void *) {
  image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

/// Reading one glTF file into a scene.
class GltfReader {
 public:
  GltfReader(Scene &scene, std::string path, const InputLocation &fileFrom)
      : scene_(scene), path_(std::move(path)), directory_(fs::path(path_).parent_path()) {
    std::error_code ec;
    std::ifstream in(path_, std::ios::binary);
    if (!fs::is_regular_file(path_, ec) || !in) throw InputError(fileFrom, "cannot open glTF file '" + path_ + "'");
    bytes_.assign(std::istreambuf_iterator<char>(in), {});
    binary_ = bytes_.size() >= 4 && std::memcmp(bytes_.data(), "glTF", 4) == 0;
    const std::string text =
        binary_ ? glbJson(bytes_, at("")) : std::string(reinterpret_cast<const char *>(bytes_.data()), bytes_.size());
    json_ = parseJsonText(text, path_);
    root_ = std::make_unique<JsonNode>(json_, path_, "");
    root_->expectObject();
    checkAsset();
    checkBufferViews();
    loadBuffers();
  }

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
  InputLocation at(const std::string &jsonPath) const { return {path_, 0, 0, jsonPath}; }

  /// The array at top-level `key`, or an empty list.
  std::vector<JsonNode> list(const std::string &key) const {
    return root_->has(key) ? root_->child(key).asArray() : std::vector<JsonNode>{};
  }
  /// Element `index` of the top-level array `key`, named by `reference` (the
  /// JSON path that holds the index) when it does not exist.
  JsonNode entry(const std::string &key, const JsonNode &reference) const {
    const int64_t index = reference.asInteger(0, INT32_MAX);
    const size_t count = root_->has(key) ? root_->child(key).asArray().size() : 0;
    if (size_t(index) >= count)
      reference.fail(fmt::format("{} {} does not exist (the file has {})", key, index, count));
    return root_->child(key).element(size_t(index));
  }

  void checkAsset() {
    JsonNode asset = root_->child("asset");
    const std::string version = asset.child("version").asString();
    if (version.rfind("2.", 0) != 0)
      asset.child("version").fail("glTF version " + version + "; Radiant reads glTF 2.0");
    // An extension the file says it needs and Radiant does not read changes what the data means.
    static const std::set<std::string> kRead = {"KHR_materials_emissive_strength", "KHR_materials_transmission",
                                                "KHR_materials_ior", "KHR_materials_unlit", "KHR_mesh_quantization"};
    if (root_->has("extensionsRequired"))
      for (const JsonNode &name : root_->child("extensionsRequired").asArray())
        if (!kRead.count(name.asString()))
          name.fail("the file requires the extension " + name.asString() +
                    ", which Radiant does not read (for compressed meshes, decompress them first, e.g. with "
                    "gltf-transform)");
  }

  /// Every buffer view inside its buffer's byteLength, before tinygltf reads images through them.
  void checkBufferViews() {
    std::vector<JsonNode> buffers = list("buffers");
    std::vector<uint64_t> lengths;
    for (const JsonNode &buffer : buffers)
      lengths.push_back(uint64_t(buffer.child("byteLength").asInteger(0, INT64_MAX)));
    for (const JsonNode &view : list("bufferViews")) {
      const JsonNode buffer = entry("buffers", view.child("buffer"));
      const uint64_t capacity = lengths[size_t(view.child("buffer").asInteger(0, INT32_MAX))];
      const uint64_t offset = uint64_t(view.integer("byteOffset", 0, 0, INT64_MAX));
      const uint64_t length = uint64_t(view.child("byteLength").asInteger(1, INT64_MAX));
      if (offset > capacity || length > capacity - offset)
        view.fail(fmt::format("bytes {} to {} of buffer {}, which has {} bytes", offset, offset + length,
                              view.child("buffer").value().dump(), capacity));
      if (view.has("byteStride")) {
        const int64_t stride = view.integer("byteStride", 0, 4, 252);
        if (stride % 4 != 0) view.child("byteStride").fail("byteStride must be a multiple of 4");
      }
    }
    for (const JsonNode &image : list("images"))
      if (image.has("bufferView")) entry("bufferViews", image.child("bufferView"));
  }

  void loadBuffers() {
    tinygltf::TinyGLTF gltf;
    gltf.SetImageLoader(&keepImageBytes, nullptr);
    std::string error, warning;
    const std::string base = directory_.string();
    const bool ok =
        binary_ ? gltf.LoadBinaryFromMemory(&model_, &error, &warning, bytes_.data(),
                                            static_cast<unsigned int>(bytes_.size()), base)
                : gltf.LoadASCIIFromString(&model_, &error, &warning, reinterpret_cast<const char *>(bytes_.data()),
                                           static_cast<unsigned int>(bytes_.size()), base);
    auto trimmed = [](std::string s) {
      while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
      std::replace(s.begin(), s.end(), '\n', ';');
      return s;
    };
    if (!ok || !error.empty()) throw InputError(at(""), "cannot read the glTF data (tinygltf: " + trimmed(error) + ")");
    if (!warning.empty()) scene_.warnings.push_back(path_ + ": tinygltf: " + trimmed(warning));
    std::vector<JsonNode> buffers = list("buffers");
    if (model_.buffers.size() != buffers.size())
      throw InputError(at("/buffers"), "tinygltf read a different number of buffers than the file lists");
    for (size_t b = 0; b < buffers.size(); ++b)
      if (uint64_t(model_.buffers[b].data.size()) < uint64_t(buffers[b].child("byteLength").asInteger(0, INT64_MAX)))
        buffers[b].fail(
            fmt::format("the buffer holds {} bytes, fewer than its byteLength", model_.buffers[b].data.size()));
  }

  /// The scene's node trees, walked without recursion (a file may nest
  /// thousands of nodes): every node with a mesh becomes an instance, and
  /// the camera of the lowest-numbered node that has one becomes the view.
  void collectInstances(const Transform &toWorld) {
    const std::vector<JsonNode> nodes = list("nodes");
    std::vector<JsonNode> roots;
    if (root_->has("scenes") && !list("scenes").empty()) {
      JsonNode sceneNode = root_->has("scene") ? entry("scenes", root_->child("scene")) : list("scenes")[0];
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
          scene_.warnings.push_back(path_ + ": the " + type + " camera at " + camera.path() +
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

  /// The accessor at `reference` (a primitive's attribute or indices), checked
  /// against its buffer view and buffer.
  AccessorView accessor(const JsonNode &reference, const std::vector<int> &components,
                        const std::vector<int> &componentTypes, bool allowNormalized = true) {
    JsonNode node = entry("accessors", reference);
    AccessorView view;
    view.path = node.path();
    if (node.has("sparse")) node.child("sparse").fail("sparse accessors are not read");
    if (!node.has("bufferView")) node.fail("an accessor without a bufferView (all zeros) is not read");
    view.componentType = int(node.child("componentType").asInteger(0, INT32_MAX));
    view.components = componentsOf(node.child("type").asString());
    view.normalized = node.has("normalized") && node.child("normalized").value().is_boolean() &&
                      node.child("normalized").value().get<bool>();
    view.count = size_t(node.child("count").asInteger(0, INT64_MAX));
    std::string accepted;
    for (int type : componentTypes) accepted += (accepted.empty() ? "" : ", ") + std::string(componentName(type));
    if (std::find(componentTypes.begin(), componentTypes.end(), view.componentType) == componentTypes.end() ||
        (view.normalized && !allowNormalized))
      node.child("componentType")
          .fail(fmt::format("componentType {} ({}{}) is not read for {}; expected {}", view.componentType,
                            componentName(view.componentType), view.normalized ? ", normalized" : "", reference.path(),
                            accepted));
    if (std::find(components.begin(), components.end(), view.components) == components.end())
      node.child("type").fail(fmt::format("type {} is not read for {}; expected {}", node.child("type").asString(),
                                          reference.path(), typeName(components.front())));
    JsonNode bufferView = entry("bufferViews", node.child("bufferView"));
    const size_t viewIndex = size_t(node.child("bufferView").asInteger(0, INT32_MAX));
    const size_t elementSize = componentSize(view.componentType) * size_t(view.components);
    view.stride = bufferView.has("byteStride") ? size_t(bufferView.child("byteStride").asInteger(4, 252)) : elementSize;
    if (view.stride < elementSize)
      bufferView.child("byteStride")
          .fail(fmt::format("byteStride {} is smaller than the {} bytes of {}'s elements", view.stride, elementSize,
                            view.path));
    const uint64_t viewLength = uint64_t(bufferView.child("byteLength").asInteger(1, INT64_MAX));
    const uint64_t offset = uint64_t(node.integer("byteOffset", 0, 0, INT64_MAX));
    // In 64 bits without overflow: count ≤ 2⁶³ and stride ≤ 252, so compare by division first.
    const bool fits =
        view.count == 0 || (offset <= viewLength && (view.count - 1) <= (viewLength - offset) / view.stride &&
                            offset + (view.count - 1) * view.stride + elementSize <= viewLength);
    if (!fits)
      node.fail(
          fmt::format("count {} exceeds buffer view {} ({} elements of {} bytes, {} apart from byte {}, need "
                      "more than its {} bytes)",
                      view.count, viewIndex, view.count, elementSize, view.stride, offset, viewLength));
    const size_t bufferIndex = size_t(bufferView.child("buffer").asInteger(0, INT32_MAX));
    const std::vector<unsigned char> &data = model_.buffers[bufferIndex].data;
    const uint64_t viewOffset = uint64_t(bufferView.integer("byteOffset", 0, 0, INT64_MAX));
    if (viewOffset + viewLength > data.size())  // checked by checkBufferViews and loadBuffers; kept as the last guard
      bufferView.fail("runs past the end of its buffer's data");
    view.data = data.data() + viewOffset + offset;
    return view;
  }

  /// The instances' triangles, counted before any is added.
  void countTriangles() {
    uint64_t total = 0;
    std::map<size_t, uint64_t> perMesh;
    for (const Instance &instance : instances_) {
      auto [it, inserted] = perMesh.try_emplace(instance.mesh, 0);
      if (inserted) {
        JsonNode mesh = root_->child("meshes").element(instance.mesh);
        for (const JsonNode &primitive : mesh.child("primitives").asArray()) {
          const int mode = primitiveMode(primitive);
          JsonNode countFrom = primitive.has("indices")
                                   ? entry("accessors", primitive.child("indices"))
                                   : entry("accessors", primitive.child("attributes").child("POSITION"));
          const uint64_t count = uint64_t(countFrom.child("count").asInteger(0, INT64_MAX));
          it->second += mode == 4 ? count / 3 : (count >= 3 ? count - 2 : 0);
        }
      }
      total += it->second;
      if (total > kMaxGltfTriangles)
        throw InputError(at("/nodes/" + std::to_string(instance.node)),
                         fmt::format("the scene's meshes, placed by its nodes, have more than {} triangles; "
                                     "Radiant reads at most {}",
                                     total, kMaxGltfTriangles));
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
    JsonNode node = root_->child("nodes").element(instance.node);
    JsonNode mesh = root_->child("meshes").element(instance.mesh);
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
    scene_.objects.push_back(SceneObject{objectNameFor(instance),
                                         fmt::format("{} (node {}, mesh {})", path_, instance.node, instance.mesh)});
    const bool flip = instance.toWorld.determinant() < 0;
    JsonNode mesh = root_->child("meshes").element(instance.mesh);
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
                        path_, primitive.path(), n, n % 3));
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

  // Materials ---------------------------------------------------------------

  uint32_t materialFor(const JsonNode &primitive) {
    if (!primitive.has("material"))
      return defaultMaterial_ >= 0 ? uint32_t(defaultMaterial_) : detail::defaultMaterialIndex(scene_);
    JsonNode material = entry("materials", primitive.child("material"));
    const size_t index = size_t(primitive.child("material").asInteger(0, INT32_MAX));
    if (auto it = materials_.find(index); it != materials_.end()) return it->second;
    // A material of the same name in the JSON scene wins, as over an MTL material.
    const std::string base = material.string("name", "");
    const std::string name = base.empty() ? "material-" + std::to_string(index) : base;
    const int existing = detail::findMaterial(scene_, name);
    if (existing >= 0 && size_t(existing) < overridableMaterials_) return materials_[index] = uint32_t(existing);
    Material converted = convertMaterial(material, index);
    converted.name = name;
    // Another file's material of the same name (Blender names every first material "Material") stays its own.
    if (existing >= 0) converted.name = objectName_ + "/" + name;
    while (detail::findMaterial(scene_, converted.name) >= 0) converted.name += "#" + std::to_string(index);
    scene_.materials.push_back(std::move(converted));
    return materials_[index] = uint32_t(scene_.materials.size() - 1);
  }

  /// A number in an extension object of the material, or `fallback`.
  static double extensionNumber(const JsonNode &material, const char *extension, const char *key, double fallback) {
    if (!material.has("extensions") || !material.child("extensions").has(extension)) return fallback;
    return material.child("extensions").child(extension).number(key, fallback);
  }

  static Bands colour(const JsonNode &node, const char *key, size_t size, double fallback) {
    if (!node.has(key)) return Bands(fallback);
    std::vector<JsonNode> values = node.child(key).asArray(size, size);
    Bands result;
    for (int b = 0; b < kBandCount; ++b) {
      result[b] = values[size_t(b)].asNumber();
      if (result[b] < 0) values[size_t(b)].fail("a colour factor must be ≥ 0");
    }
    return result;
  }

  Material convertMaterial(const JsonNode &node, size_t index) {
    Material m;
    m.definedAt = node.location();
    detail::MaterialFieldNames names{"baseColorFactor", "baseColorFactor", "emissiveFactor × emissiveStrength",
                                     "KHR_materials_ior ior", "roughnessFactor"};
    const JsonNode pbr = node.has("pbrMetallicRoughness")
                             ? node.child("pbrMetallicRoughness")
                             : JsonNode(emptyObject_, path_, node.path() + "/pbrMetallicRoughness");
    const Bands base = colour(pbr, "baseColorFactor", 4, 1.0);
    const double metallic = pbr.number("metallicFactor", 1.0), roughness = pbr.number("roughnessFactor", 1.0);
    const double transmission = extensionNumber(node, "KHR_materials_transmission", "transmissionFactor", 0.0);
    m.emission = colour(node, "emissiveFactor", 3, 0.0) *
                 extensionNumber(node, "KHR_materials_emissive_strength", "emissiveStrength", 1.0);
    const bool textured = pbr.has("baseColorTexture");
    if (transmission > 0) {
      m.kind = MaterialKind::Dielectric;
      m.ior = extensionNumber(node, "KHR_materials_ior", "ior", 1.5);
      m.specular = base;  // glTF tints transmitted light by the base colour
      m.diffuse = Bands(0.0);
    } else if (metallic >= 0.99 && roughness <= 0.01) {
      m.kind = MaterialKind::Mirror;
      m.specular = base;
      m.diffuse = Bands(0.0);
    } else {
      // The rough lobes of the metallic-roughness model are read as Lambertian with the base colour.
      m.kind = MaterialKind::Lambertian;
      m.diffuse = base;
      // ρ ≥ 1 makes radiosity diverge; white (glTF's default) is taken down to just below, keeping the colour.
      // With a texture, ρ = factor × texel is clamped per texel instead.
      if (!textured && base.max() > kMaxDiffuseReflectance) m.diffuse = base * (kMaxDiffuseReflectance / base.max());
    }
    if (node.has("extras") && node.child("extras").has("radiant")) {
      readRadiantExtras(node.child("extras").child("radiant"), m);
      names = detail::MaterialFieldNames{};
      names.diffuse = "extras.radiant.diffuse";
      names.specular = "extras.radiant.specular";
      names.emission = "extras.radiant.emission";
      names.ior = "extras.radiant.ior";
      names.roughness = "extras.radiant.roughness";
    }
    if (textured) setTexture(pbr.child("baseColorTexture"), m);
    if (node.has("emissiveTexture") && !emissiveTextureWarned_) {
      emissiveTextureWarned_ = true;
      scene_.warnings.push_back(path_ + ": " + node.path() +
                                ": emissiveTexture is not read (emission is uniform: emissiveFactor × strength)");
    }
    (void)index;
    detail::checkMaterial(m, m.definedAt, names);
    return m;
  }

  /// extras.radiant, written by radiant export (docs/export.md): the material as Radiant defines it.
  void readRadiantExtras(const JsonNode &radiant, Material &m) {
    radiant.expectObject();
    const std::string kind = radiant.string("kind", materialKindName(m.kind));
    static const MaterialKind kKinds[] = {MaterialKind::Lambertian, MaterialKind::Mirror, MaterialKind::Dielectric,
                                          MaterialKind::Glossy};
    std::vector<std::string> known;
    bool found = false;
    for (MaterialKind k : kKinds) {
      known.push_back(materialKindName(k));
      if (kind == materialKindName(k)) m.kind = k, found = true;
    }
    if (!found) radiant.child("kind").fail("unknown material kind '" + kind + "'" + didYouMean(kind, known));
    m.diffuse = radiant.bands(
        "diffuse", m.kind == MaterialKind::Lambertian || m.kind == MaterialKind::Glossy ? m.diffuse : Bands(0.0));
    m.specular = radiant.bands("specular", m.specular);
    m.ior = radiant.number("ior", m.ior);
    m.roughness = radiant.number("roughness", m.roughness);
    m.emission = radiant.bands("emission", m.emission);
  }

  void setTexture(const JsonNode &info, Material &m) {
    JsonNode texture = entry("textures", info.child("index"));
    if (info.integer("texCoord", 0, 0, INT32_MAX) != 0)
      scene_.warnings.push_back(path_ + ": " + info.path() + ": texCoord " + info.child("texCoord").value().dump() +
                                " is read as TEXCOORD_0 (Radiant reads one set of texture coordinates)");
    if (info.has("extensions") && info.child("extensions").has("KHR_texture_transform"))
      scene_.warnings.push_back(path_ + ": " + info.path() + ": KHR_texture_transform is not read");
    if (!texture.has("source")) texture.fail("a texture without a source image");
    JsonNode image = entry("images", texture.child("source"));
    const size_t imageIndex = size_t(texture.child("source").asInteger(0, INT32_MAX));
    TextureWrap wrap = TextureWrap::Repeat;
    if (texture.has("sampler")) {
      JsonNode sampler = entry("samplers", texture.child("sampler"));
      const int64_t wrapS = sampler.integer("wrapS", 10497, 0, INT32_MAX),
                    wrapT = sampler.integer("wrapT", 10497, 0, INT32_MAX);
      if (wrapS == 33648 || wrapT == 33648)
        scene_.warnings.push_back(path_ + ": " + sampler.path() +
                                  ": MIRRORED_REPEAT is read as REPEAT (Radiant repeats or clamps)");
      if (wrapS != wrapT)
        scene_.warnings.push_back(path_ + ": " + sampler.path() +
                                  ": wrapS and wrapT differ; Radiant wraps both as wrapS says");
      m.textureWrap = wrapS == 33071 ? TextureWrap::Clamp : TextureWrap::Repeat;
      wrap = m.textureWrap;
    }
    m.diffuseTextureFrom = image.location();
    if (image.has("uri") && image.child("uri").asString().rfind("data:", 0) != 0) {
      // An image file beside the glTF: loaded with the scene's other textures.
      const std::string uri = image.child("uri").asString();
      fs::path file = directory_ / decodeUri(uri);
      std::error_code ec;
      if (!fs::is_regular_file(file, ec)) image.child("uri").fail("cannot open image '" + file.string() + "'");
      m.diffuseTexture = file.lexically_normal().string();
      m.diffuseTextureFrom = image.child("uri").location();
      return;
    }
    // Embedded (a buffer view or a data: URI): decoded here, once per wrap mode.
    m.diffuseTexture = path_ + " " + image.path();
    const auto key = std::make_pair(imageIndex, wrap);
    if (auto it = textures_.find(key); it != textures_.end()) {
      m.diffuseTextureIndex = it->second;
      return;
    }
    if (imageIndex >= model_.images.size()) image.fail("tinygltf did not read this image");
    const std::vector<unsigned char> &bytes = model_.images[imageIndex].image;
    scene_.textures.push_back(Texture::decode(bytes, image.location(), TextureEncoding::Colour, wrap));
    m.diffuseTextureIndex = textures_[key] = int(scene_.textures.size()) - 1;
  }

  /// A URI's percent-escapes (%20 → space), as glTF writes relative file names.
  static std::string decodeUri(const std::string &uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
      if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
          std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
        out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
        i += 2;
      } else {
        out += uri[i];
      }
    }
    return out;
  }

  Scene &scene_;
  std::string path_;
  fs::path directory_;
  std::vector<unsigned char> bytes_;
  bool binary_ = false;
  Json json_;
  const Json emptyObject_ = Json::object();
  std::unique_ptr<JsonNode> root_;
  tinygltf::Model model_;

  std::string objectName_;
  int defaultMaterial_ = -1;
  size_t overridableMaterials_ = 0;
  std::vector<Instance> instances_;
  std::vector<size_t> rootIndices_;
  detail::GltfView view_;
  std::map<size_t, uint32_t> materials_;                    ///< glTF material → scene material
  std::map<std::pair<size_t, TextureWrap>, int> textures_;  ///< glTF image and wrap → scene texture
  std::set<std::string> objectNames_;
  bool orthographicWarned_ = false, emissiveTextureWarned_ = false;
};

}  // namespace

detail::GltfView detail::appendGltf(Scene &scene, const std::string &path, const Transform &toWorld,
                                    const std::string &objectName, int defaultMaterial, size_t overridableMaterials,
                                    const InputLocation &fileFrom) {
  GltfReader reader(scene, path, fileFrom);
  return reader.append(toWorld, objectName, defaultMaterial, overridableMaterials);
}

}  // namespace radiant
