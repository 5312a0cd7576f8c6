// A glTF 2.0 file opened for reading (load_gltf.cpp, gltf_material.cpp): its
// JSON, read through JsonNode so that every refusal names the file and the
// JSON path inside it, and its buffers and image bytes, which tinygltf reads
// (the GLB's BIN chunk, data: URIs, external .bin and image files). Not a
// public API.
#pragma once

#include <tiny_gltf.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "scene/json_reader.h"
#include "scene/scene.h"

namespace radiant::gltf {

inline constexpr int kComponentByte = 5120, kComponentUnsignedByte = 5121, kComponentShort = 5122,
                     kComponentUnsignedShort = 5123, kComponentUnsignedInt = 5125, kComponentFloat = 5126;

/// Bytes per component of a glTF componentType, 0 for one Radiant does not read.
size_t componentSize(int type);

/// A URI's percent-escapes (%20 → space), as glTF writes relative file names.
std::string decodeUri(const std::string &uri);

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

/// The file: checked as far as can be before tinygltf runs, then its buffers read.
class GltfFile {
 public:
  /// Reads `path` (.gltf or .glb, told apart by the GLB signature). `fileFrom`
  /// locates the reference to a file that cannot be opened; tinygltf's
  /// warnings go to `warnings`.
  GltfFile(std::string path, const InputLocation &fileFrom, std::vector<std::string> &warnings);

  const std::string &path() const { return path_; }
  const std::filesystem::path &directory() const { return directory_; }
  const JsonNode &root() const { return *root_; }
  InputLocation at(const std::string &jsonPath) const { return {path_, 0, 0, jsonPath}; }

  /// The array at top-level `key`, or an empty list.
  std::vector<JsonNode> list(const std::string &key) const;
  /// Element `index` of the top-level array `key`, where `reference` holds
  /// the index; fails at `reference` when there is no such element.
  JsonNode entry(const std::string &key, const JsonNode &reference) const;
  /// The accessor at `reference` (a primitive's attribute or indices), checked
  /// to have one of `components` per element and one of `componentTypes`, and
  /// to lie inside its buffer view and buffer, before a byte of it is read.
  AccessorView accessor(const JsonNode &reference, const std::vector<int> &components,
                        const std::vector<int> &componentTypes, bool allowNormalized = true) const;
  /// The encoded bytes of image `index` (embedded, or a file tinygltf read).
  const std::vector<unsigned char> &imageBytes(size_t index, const JsonNode &image) const;
  /// An empty JSON object at `path`, for optional objects such as pbrMetallicRoughness.
  JsonNode emptyObject(const std::string &path) const { return JsonNode(emptyObject_, path_, path); }

 private:
  void checkAsset();
  /// The parts of the glTF schema tinygltf insists on, each refusal at its JSON path (gltf_schema.cpp).
  void checkSchema() const;
  void checkBufferViews();
  void loadBuffers(std::vector<std::string> &warnings);

  std::string path_;
  std::filesystem::path directory_;
  std::vector<unsigned char> bytes_;
  bool binary_ = false;
  Json json_;
  const Json emptyObject_ = Json::object();
  std::unique_ptr<JsonNode> root_;
  tinygltf::Model model_;
};

/// glTF image and wrap mode → index in Scene::textures: each embedded image decoded once per wrap.
using TextureCache = std::map<std::pair<size_t, TextureWrap>, int>;

/// A glTF material (`node`, at /materials/N) as a Radiant material, without
/// its name: extras.radiant when present, otherwise the metallic-roughness
/// approximation; the base colour texture set (an embedded image decoded
/// into scene.textures). Warnings go to scene.warnings.
Material convertMaterial(const GltfFile &file, const JsonNode &node, Scene &scene, TextureCache &textures);

}  // namespace radiant::gltf
