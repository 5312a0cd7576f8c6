// GltfFile::checkSchema: the parts of the glTF 2.0 schema (Khronos, glTF 2.0
// specification, section 5) that tinygltf insists on, checked before it runs,
// so that a refusal names the file and the JSON path of what is wrong. tinygltf
// refuses the same mistakes, but in words of its own without a position
// ("'count' property is not a positive integer"): 177 of 1 451 refusals of
// tools/error_corpus.py's glTF cases named no path before this check.

#include <fmt/format.h>

#include <set>
#include <string>

#include "scene/gltf_file.h"

namespace radiant::gltf {

namespace {

/// Every element of the top-level array `key` must be an object.
std::vector<JsonNode> objects(const GltfFile &file, const std::string &key) {
  std::vector<JsonNode> list = file.list(key);
  for (const JsonNode &entry : list) entry.expectObject();
  return list;
}

/// An optional array of `size` finite numbers at `key`.
void numbers(const JsonNode &node, const std::string &key, size_t size) {
  if (!node.has(key)) return;
  for (const JsonNode &n : node.child(key).asArray(size, size)) n.asNumber();
}

/// A textureInfo (baseColorTexture, emissiveTexture, …): an object with an index of a texture.
void textureInfo(const GltfFile &file, const JsonNode &parent, const std::string &key) {
  if (!parent.has(key)) return;
  const JsonNode info = parent.child(key);
  info.expectObject();
  file.entry("textures", info.child("index"));
  info.integer("texCoord", 0, 0, INT32_MAX);
}

void checkAccessors(const GltfFile &file) {
  static const std::set<int64_t> kComponentTypes = {kComponentByte,          kComponentUnsignedByte, kComponentShort,
                                                    kComponentUnsignedShort, kComponentUnsignedInt,  kComponentFloat};
  static const std::set<std::string> kTypes = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
  for (const JsonNode &accessor : objects(file, "accessors")) {
    accessor.child("count").asInteger(1, INT64_MAX);
    const JsonNode componentType = accessor.child("componentType");
    if (!kComponentTypes.count(componentType.asInteger(0, INT32_MAX)))
      componentType.fail(fmt::format("componentType {} is not one of glTF's (5120, 5121, 5122, 5123, 5125, 5126)",
                                     componentType.value().dump()));
    const JsonNode type = accessor.child("type");
    if (!kTypes.count(type.asString()))
      type.fail("type \"" + type.asString() + "\" is not one of SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3, MAT4");
    if (accessor.has("bufferView")) file.entry("bufferViews", accessor.child("bufferView"));
    accessor.integer("byteOffset", 0, 0, INT64_MAX);
  }
}

void checkMeshes(const GltfFile &file) {
  for (const JsonNode &mesh : objects(file, "meshes"))
    for (const JsonNode &primitive : mesh.child("primitives").asArray(1)) {
      primitive.expectObject();
      const JsonNode attributes = primitive.child("attributes");
      attributes.expectObject();
      for (const auto &[name, value] : attributes.value().items()) file.entry("accessors", attributes.child(name));
      if (primitive.has("indices")) {
        const JsonNode indices = file.entry("accessors", primitive.child("indices"));
        if (!indices.has("bufferView"))
          indices.fail("the accessor of a primitive's indices needs a bufferView (it is " +
                       primitive.child("indices").path() + ")");
      }
      if (primitive.has("material")) file.entry("materials", primitive.child("material"));
      primitive.integer("mode", 4, 0, 6);
    }
}

void checkMaterials(const GltfFile &file) {
  for (const JsonNode &material : objects(file, "materials")) {
    numbers(material, "emissiveFactor", 3);
    textureInfo(file, material, "emissiveTexture");
    textureInfo(file, material, "normalTexture");
    textureInfo(file, material, "occlusionTexture");
    if (!material.has("pbrMetallicRoughness")) continue;
    const JsonNode pbr = material.child("pbrMetallicRoughness");
    pbr.expectObject();
    numbers(pbr, "baseColorFactor", 4);
    textureInfo(file, pbr, "baseColorTexture");
    textureInfo(file, pbr, "metallicRoughnessTexture");
  }
}

void checkCameras(const GltfFile &file) {
  for (const JsonNode &camera : objects(file, "cameras")) {
    const std::string type = camera.child("type").asString();
    if (type != "perspective" && type != "orthographic")
      camera.child("type").fail("camera type \"" + type + "\" is neither \"perspective\" nor \"orthographic\"");
    const JsonNode projection = camera.child(type);
    projection.expectObject();
    if (type == "perspective") {
      projection.child("yfov").asNumber();
      projection.child("znear").asNumber();
    } else {
      for (const char *key : {"xmag", "ymag", "znear", "zfar"}) projection.child(key).asNumber();
    }
  }
}

void checkImagesAndTextures(const GltfFile &file) {
  for (const JsonNode &image : objects(file, "images"))
    if (!image.has("uri") && !image.has("bufferView"))
      image.fail("an image needs a \"uri\" or a \"bufferView\"");
    else if (image.has("uri"))
      image.child("uri").asString();
  objects(file, "samplers");
  for (const JsonNode &texture : objects(file, "textures")) {
    if (texture.has("source")) file.entry("images", texture.child("source"));
    if (texture.has("sampler")) file.entry("samplers", texture.child("sampler"));
  }
}

void checkNodesAndScenes(const GltfFile &file) {
  for (const JsonNode &node : objects(file, "nodes")) {
    if (node.has("mesh")) file.entry("meshes", node.child("mesh"));
    if (node.has("camera")) file.entry("cameras", node.child("camera"));
    if (node.has("children"))
      for (const JsonNode &child : node.child("children").asArray()) file.entry("nodes", child);
    numbers(node, "translation", 3);
    numbers(node, "rotation", 4);
    numbers(node, "scale", 3);
    numbers(node, "matrix", 16);
  }
  for (const JsonNode &scene : objects(file, "scenes"))
    if (scene.has("nodes"))
      for (const JsonNode &node : scene.child("nodes").asArray()) file.entry("nodes", node);
  if (file.root().has("scene")) file.entry("scenes", file.root().child("scene"));
}

}  // namespace

void GltfFile::checkSchema() const {
  // A .gltf file's buffers are files or data: URIs; only a GLB's first buffer may be its BIN chunk.
  for (const JsonNode &buffer : objects(*this, "buffers"))
    if (!binary_ && !buffer.has("uri")) buffer.fail("a buffer of a .gltf file needs a \"uri\" (a file or data: URI)");
  objects(*this, "bufferViews");
  checkAccessors(*this);
  checkMeshes(*this);
  checkMaterials(*this);
  checkCameras(*this);
  checkImagesAndTextures(*this);
  checkNodesAndScenes(*this);
}

}  // namespace radiant::gltf
