// GltfFile: the glTF container, the checks made before tinygltf runs, and
// accessors checked against their buffers (gltf_file.h).
//
// tinygltf 2.7 reads an image's buffer view without checking it against its
// buffer, so every buffer view is checked against its buffer's byteLength
// before tinygltf runs; after it, every buffer must hold its byteLength, and
// an accessor is checked against its buffer view when a primitive asks for
// it. A file that lies about its sizes is refused before it can make the
// loader read out of bounds.

#include "scene/gltf_file.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <set>

#include "util/input_file.h"

namespace radiant::gltf {

namespace fs = std::filesystem;

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

std::string decodeUri(const std::string &uri) {
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

namespace {

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

/// The GLB container (glTF 2.0 §4.4): a 12-byte header, a JSON chunk, an optional BIN chunk.
std::string glbJson(const std::vector<unsigned char> &bytes, const InputLocation &where) {
  auto word = [&](size_t at) {
    uint32_t value;
    std::memcpy(&value, bytes.data() + at, 4);
    return value;
  };
  if (bytes.size() < 20) throw InputError(where, fmt::format("a GLB file of {} bytes is truncated", bytes.size()));
  if (word(4) != 2)
    throw InputError(where, fmt::format("'{}' is a GLB of version {}{}, which Radiant does not read: it reads glTF 2.0",
                                        where.file, word(4), word(4) == 1 ? " (glTF 1.0)" : ""));
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

/// tinygltf's file access (external buffers and images) through
/// readInputFile: its own opens a name with fopen and ifstream, which block
/// forever on a FIFO. Only reading is allowed.
bool gltfFileExists(const std::string &path, void *) {
  return checkInputFile(path).status != InputFileRead::Status::Missing;
}
std::string gltfExpandFilePath(const std::string &path, void *) {
  return path;
}
bool gltfReadWholeFile(std::vector<unsigned char> *out, std::string *error, const std::string &path, void *) {
  InputFileRead read = tryReadInputFile(path);
  if (!read.ok()) {
    if (error) *error += inputFileProblem(read, "file '" + path + "'");
    return false;
  }
  out->assign(read.bytes.begin(), read.bytes.end());
  return true;
}
bool gltfRefuseWrite(std::string *error, const std::string &path, const std::vector<unsigned char> &, void *) {
  if (error) *error += "not writing '" + path + "' while reading";
  return false;
}

}  // namespace

GltfFile::GltfFile(std::string path, const InputLocation &fileFrom, std::vector<std::string> &warnings)
    : path_(std::move(path)), directory_(fs::path(path_).parent_path()) {
  const std::string bytes = readInputFile(path_, fileFrom, "glTF file");
  bytes_.assign(bytes.begin(), bytes.end());
  binary_ = bytes_.size() >= 4 && std::memcmp(bytes_.data(), "glTF", 4) == 0;
  const std::string text =
      binary_ ? glbJson(bytes_, at("")) : std::string(reinterpret_cast<const char *>(bytes_.data()), bytes_.size());
  json_ = parseJsonText(text, path_);
  root_ = std::make_unique<JsonNode>(json_, path_, "");
  root_->expectObject();
  checkAsset();
  checkSchema();
  checkBufferViews();
  loadBuffers(warnings);
}

/// The array at top-level `key`, or an empty list.
std::vector<JsonNode> GltfFile::list(const std::string &key) const {
  return root_->has(key) ? root_->child(key).asArray() : std::vector<JsonNode>{};
}
/// Element `index` of the top-level array `key`, named by `reference` (the
/// JSON path that holds the index) when it does not exist.
JsonNode GltfFile::entry(const std::string &key, const JsonNode &reference) const {
  const int64_t index = reference.asInteger(0, INT32_MAX);
  size_t count = 0;
  if (root_->has(key)) {
    JsonNode array = root_->child(key);
    if (!array.value().is_array()) array.asArray();  // fails: "expected an array"
    count = array.size();                            // without copying the array (files list 10⁵ nodes)
  }
  if (size_t(index) >= count) reference.fail(fmt::format("{} {} does not exist (the file has {})", key, index, count));
  return root_->child(key).element(size_t(index));
}

void GltfFile::checkAsset() {
  JsonNode asset = root_->child("asset");
  // glTF 1.0 wrote its version as a number or as "1.0" (CesiumMilkTruck); its
  // materials (techniques and shaders) and buffer layout are not 2.0's.
  const JsonNode versionNode = asset.child("version");
  const Json &value = versionNode.value();
  if (value.is_number() || (value.is_string() && value.get<std::string>().rfind("1.", 0) == 0))
    versionNode.fail(
        fmt::format("'{}' is a glTF 1.0 file ({}), which Radiant does not read: it reads glTF 2.0 "
                    "(convert the file, e.g. with gltf-pipeline or Blender)",
                    path_, value.dump()));
  const std::string version = versionNode.asString();
  if (version.rfind("2.", 0) != 0)
    versionNode.fail(
        fmt::format("'{}' is glTF version {}, which Radiant does not read: it reads glTF 2.0", path_, version));
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
void GltfFile::checkBufferViews() {
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

void GltfFile::loadBuffers(std::vector<std::string> &warnings) {
  // A buffer file that is not a regular file is named with its JSON path here;
  // tinygltf, through gltfReadWholeFile, would refuse it too, without the path.
  const std::vector<JsonNode> buffers = list("buffers");
  for (const JsonNode &buffer : buffers) {
    if (!buffer.has("uri") || buffer.child("uri").asString().rfind("data:", 0) == 0) continue;
    const std::string file = (directory_ / decodeUri(buffer.child("uri").asString())).string();
    if (const InputFileRead read = checkInputFile(file); read.status == InputFileRead::Status::NotRegular)
      buffer.child("uri").fail(inputFileProblem(read, "buffer file '" + file + "'"));
  }
  tinygltf::TinyGLTF gltf;
  gltf.SetImageLoader(&keepImageBytes, nullptr);
  gltf.SetFsCallbacks({&gltfFileExists, &gltfExpandFilePath, &gltfReadWholeFile, &gltfRefuseWrite, nullptr});
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
  if (!warning.empty()) warnings.push_back(path_ + ": tinygltf: " + trimmed(warning));
  if (model_.buffers.size() != buffers.size())
    throw InputError(at("/buffers"), "tinygltf read a different number of buffers than the file lists");
  for (size_t b = 0; b < buffers.size(); ++b)
    if (uint64_t(model_.buffers[b].data.size()) < uint64_t(buffers[b].child("byteLength").asInteger(0, INT64_MAX)))
      buffers[b].fail(
          fmt::format("the buffer holds {} bytes, fewer than its byteLength", model_.buffers[b].data.size()));
}

/// The accessor at `reference` (a primitive's attribute or indices), checked
/// against its buffer view and buffer.
AccessorView GltfFile::accessor(const JsonNode &reference, const std::vector<int> &components,
                                const std::vector<int> &componentTypes, bool allowNormalized) const {
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

const std::vector<unsigned char> &GltfFile::imageBytes(size_t index, const JsonNode &image) const {
  if (index >= model_.images.size()) image.fail("tinygltf did not read this image");
  return model_.images[index].image;
}

}  // namespace radiant::gltf
