#include "export/gltf_writer.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "io/image.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/file_extension.h"
#include "util/input_file.h"

namespace radiant {

namespace {

using tinygltf::Value;

constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

Value number(double x) {
  return Value(x);
}
Value triple(const Bands &b) {
  return Value(Value::Array{number(b[0]), number(b[1]), number(b[2])});
}

/// Appends `bytes` to the model's one buffer, 4-byte aligned, as a buffer view.
int addBufferView(tinygltf::Model &model, const void *bytes, size_t size, int target) {
  std::vector<unsigned char> &data = model.buffers[0].data;
  data.resize((data.size() + 3) / 4 * 4, 0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = size;
  view.target = target;
  const auto *begin = static_cast<const unsigned char *>(bytes);
  data.insert(data.end(), begin, begin + size);
  model.bufferViews.push_back(view);
  return int(model.bufferViews.size() - 1);
}

/// A float accessor of `components` per element (VEC2, VEC3).
int addFloatAccessor(tinygltf::Model &model, const std::vector<float> &values, int components, bool bounds) {
  tinygltf::Accessor accessor;
  accessor.bufferView = addBufferView(model, values.data(), values.size() * sizeof(float), kArrayBuffer);
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  accessor.count = values.size() / size_t(components);
  accessor.type = components == 2 ? TINYGLTF_TYPE_VEC2 : TINYGLTF_TYPE_VEC3;
  if (bounds) {  // POSITION must have min and max (glTF 2.0 §5.1.1)
    accessor.minValues.assign(size_t(components), INFINITY);
    accessor.maxValues.assign(size_t(components), -INFINITY);
    for (size_t i = 0; i < values.size(); ++i) {
      const size_t c = i % size_t(components);
      accessor.minValues[c] = std::min(accessor.minValues[c], double(values[i]));
      accessor.maxValues[c] = std::max(accessor.maxValues[c], double(values[i]));
    }
  }
  model.accessors.push_back(accessor);
  return int(model.accessors.size() - 1);
}

/// Indices as 16-bit when every vertex index fits (half the bytes), else 32-bit.
int addIndexAccessor(tinygltf::Model &model, const std::vector<uint32_t> &indices, size_t vertexCount) {
  tinygltf::Accessor accessor;
  if (vertexCount <= 65535) {
    std::vector<uint16_t> narrow(indices.begin(), indices.end());
    accessor.bufferView = addBufferView(model, narrow.data(), narrow.size() * 2, kElementArrayBuffer);
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  } else {
    accessor.bufferView = addBufferView(model, indices.data(), indices.size() * 4, kElementArrayBuffer);
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  }
  accessor.count = indices.size();
  accessor.type = TINYGLTF_TYPE_SCALAR;
  model.accessors.push_back(accessor);
  return int(model.accessors.size() - 1);
}

/// The texture as glTF holds it: the PNG or JPEG file as it is, or for any
/// other file (EXR) its linear texels sRGB-encoded into an 8-bit PNG.
std::pair<std::vector<unsigned char>, std::string> textureImage(const Scene &scene, const Material &material) {
  const std::string &path = material.diffuseTexture;
  const std::string extension = lowercaseExtension(path);
  if (extension == ".png" || extension == ".jpg" || extension == ".jpeg") {
    const std::string file = readInputFile(path, material.diffuseTextureFrom, "texture");
    return {std::vector<unsigned char>(file.begin(), file.end()), extension == ".png" ? "image/png" : "image/jpeg"};
  }
  const Texture &texture = scene.textures[size_t(material.diffuseTextureIndex)];
  std::span<const float> texels = texture.finestTexels();
  std::vector<unsigned char> encoded(texels.size());
  for (size_t i = 0; i < texels.size(); ++i)
    encoded[i] = (unsigned char)std::lround(255 * std::clamp(srgbEncode(texels[i]), 0.0, 1.0));
  try {
    return {encodePng(encoded, texture.width(), texture.height(), 3), "image/png"};
  } catch (const std::runtime_error &) {
    throw InputError(material.diffuseTextureFrom, "cannot encode texture '" + path + "' as PNG");
  }
}

/// An image in the buffer, its sampler (filtering smooth or nearest; wrapping
/// repeated or clamped) and the texture joining them; returns the texture's index.
int addImageTexture(tinygltf::Model &model, const std::vector<unsigned char> &bytes, const std::string &mimeType,
                    const std::string &name, bool smooth, bool repeat) {
  tinygltf::Image image;
  image.name = name;
  image.mimeType = mimeType;
  image.bufferView = addBufferView(model, bytes.data(), bytes.size(), 0);
  model.bufferViews.back().target = 0;  // images are not vertex data
  model.images.push_back(image);
  tinygltf::Sampler sampler;
  sampler.wrapS = sampler.wrapT = repeat ? TINYGLTF_TEXTURE_WRAP_REPEAT : TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
  sampler.magFilter = smooth ? TINYGLTF_TEXTURE_FILTER_LINEAR : TINYGLTF_TEXTURE_FILTER_NEAREST;
  sampler.minFilter = smooth ? TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR : TINYGLTF_TEXTURE_FILTER_NEAREST;
  model.samplers.push_back(sampler);
  tinygltf::Texture texture;
  texture.sampler = int(model.samplers.size() - 1);
  texture.source = int(model.images.size() - 1);
  model.textures.push_back(texture);
  return int(model.textures.size() - 1);
}

int addTexture(tinygltf::Model &model, const Scene &scene, const Material &material) {
  auto [bytes, mimeType] = textureImage(scene, material);
  return addImageTexture(model, bytes, mimeType, std::filesystem::path(material.diffuseTexture).filename().string(),
                         true, material.textureWrap != TextureWrap::Clamp);
}

/// The material in glTF's PBR terms (for other programs), unlit (so they show
/// COLOR_0, the baked light), and exactly as Radiant has it in extras.radiant.
tinygltf::Material gltfMaterial(tinygltf::Model &model, const Scene &scene, const Material &m) {
  tinygltf::Material out;
  out.name = m.name;
  auto &pbr = out.pbrMetallicRoughness;
  const Bands &base = m.kind == MaterialKind::Lambertian || m.kind == MaterialKind::Glossy ? m.diffuse : m.specular;
  pbr.baseColorFactor = {base[0], base[1], base[2], 1.0};
  pbr.metallicFactor = m.kind == MaterialKind::Mirror ? 1.0 : 0.0;
  pbr.roughnessFactor = m.kind == MaterialKind::Glossy       ? std::sqrt(m.roughness)
                        : m.kind == MaterialKind::Dielectric ? std::sqrt(m.transmissionRoughness)
                        : m.isDelta()                        ? 0.0
                                                             : 1.0;
  if (m.diffuseTextureIndex >= 0) pbr.baseColorTexture.index = addTexture(model, scene, m);
  if (m.kind == MaterialKind::Dielectric) {
    out.extensions["KHR_materials_transmission"] = Value(Value::Object{{"transmissionFactor", number(1.0)}});
    out.extensions["KHR_materials_ior"] = Value(Value::Object{{"ior", number(m.ior)}});
  }
  if (m.isEmitter()) {
    // glTF's emissiveFactor is at most 1: the rest goes into the strength, so factor × strength = L_e.
    const double largest = m.emission.max();
    const double strength = std::max(largest, 1.0);
    out.emissiveFactor = {m.emission[0] / strength, m.emission[1] / strength, m.emission[2] / strength};
    if (strength > 1)
      out.extensions["KHR_materials_emissive_strength"] = Value(Value::Object{{"emissiveStrength", number(strength)}});
  }
  // Unlit, so plain viewers show COLOR_0 (the baked light); not beside the emissive strength, which the
  // Khronos validator reports as a possible conflict: a viewer shows such an emitter as a bright emissive surface.
  if (!out.extensions.count("KHR_materials_emissive_strength"))
    out.extensions["KHR_materials_unlit"] = Value(Value::Object{});
  Value::Object radiant{{"kind", Value(std::string(materialKindName(m.kind)))},
                        {"diffuse", triple(m.diffuse)},
                        {"specular", triple(m.specular)},
                        {"ior", number(m.ior)},
                        {"roughness", number(m.roughness)},
                        {"emission", triple(m.emission)}};
  // Rough glass only, so the extras of every other material stay as they were.
  if (m.transmissionRoughness > 0) radiant["transmission_roughness"] = number(m.transmissionRoughness);
  out.extras = Value(Value::Object{{"radiant", Value(std::move(radiant))}});
  return out;
}

/// The name of the extension that carries the lightmap's irradiance and the
/// material's own colour (docs/export.md, "Lightmaps"): glTF has no ratified one.
constexpr const char *kLightmapExtension = "RADIANT_lightmap";

struct LightmapTextures {
  int display = -1, irradiance = -1;
};

LightmapTextures addLightmapTextures(tinygltf::Model &model, const GltfLightmap &lightmap) {
  // RGBE must not be blended across texels (the exponents differ): nearest; a decoder filters the floats.
  return {addImageTexture(model, lightmap.displayPng, "image/png", "lightmap", true, false),
          addImageTexture(model, lightmap.irradiancePng, "image/png", "lightmap irradiance (RGBE)", false, false)};
}

/// A material drawn with the lightmap: unlit, its base colour the display
/// image on TEXCOORD_1 (what plain viewers show); the material's own base
/// colour and texture, and the irradiance, in RADIANT_lightmap for engines
/// that light the albedo themselves (three.js: map and lightMap).
void lightmapMaterial(tinygltf::Material &material, const LightmapTextures &textures) {
  auto &pbr = material.pbrMetallicRoughness;
  Value::Object extension{
      {"irradianceTexture", Value(Value::Object{{"index", Value(textures.irradiance)}, {"texCoord", Value(1)}})},
      {"encoding", Value(std::string("rgbe"))},
      {"quantity", Value(std::string("irradiance"))},
      {"unit", Value(std::string("W/m²"))},
      {"baseColorFactor", Value(Value::Array{number(pbr.baseColorFactor[0]), number(pbr.baseColorFactor[1]),
                                             number(pbr.baseColorFactor[2])})}};
  if (pbr.baseColorTexture.index >= 0)
    extension["baseColorTexture"] =
        Value(Value::Object{{"index", Value(pbr.baseColorTexture.index)}, {"texCoord", Value(0)}});
  // The display image holds an emitter's light already (its L_e stays in extras.radiant.emission).
  material.extensions.erase("KHR_materials_emissive_strength");
  material.emissiveFactor = {0, 0, 0};
  material.extensions["KHR_materials_unlit"] = Value(Value::Object{});
  material.extensions[kLightmapExtension] = Value(std::move(extension));
  pbr.baseColorFactor = {1, 1, 1, 1};
  pbr.baseColorTexture = tinygltf::TextureInfo();
  pbr.baseColorTexture.index = textures.display;
  pbr.baseColorTexture.texCoord = 1;
}

/// The rotation that takes a glTF camera's axes (looking down −Z, +Y up) to
/// the scene camera's, as a unit quaternion (x, y, z, w).
std::vector<double> cameraRotation(const CameraSettings &camera) {
  const Vec3 forward = normalize(camera.target - camera.eye);
  const Vec3 right = normalize(cross(forward, camera.up));
  const Vec3 up = cross(right, forward);
  const Vec3 back = forward * -1.0;
  // Columns of the rotation matrix: right, up, back.
  const double m00 = right.x, m01 = up.x, m02 = back.x;
  const double m10 = right.y, m11 = up.y, m12 = back.y;
  const double m20 = right.z, m21 = up.z, m22 = back.z;
  const double trace = m00 + m11 + m22;
  double x, y, z, w;
  if (trace > 0) {
    const double s = 0.5 / std::sqrt(trace + 1.0);
    w = 0.25 / s, x = (m21 - m12) * s, y = (m02 - m20) * s, z = (m10 - m01) * s;
  } else if (m00 > m11 && m00 > m22) {
    const double s = 2.0 * std::sqrt(1.0 + m00 - m11 - m22);
    w = (m21 - m12) / s, x = 0.25 * s, y = (m01 + m10) / s, z = (m02 + m20) / s;
  } else if (m11 > m22) {
    const double s = 2.0 * std::sqrt(1.0 + m11 - m00 - m22);
    w = (m02 - m20) / s, x = (m01 + m10) / s, y = 0.25 * s, z = (m12 + m21) / s;
  } else {
    const double s = 2.0 * std::sqrt(1.0 + m22 - m00 - m11);
    w = (m10 - m01) / s, x = (m02 + m20) / s, y = (m12 + m21) / s, z = 0.25 * s;
  }
  const double n = std::sqrt(x * x + y * y + z * z + w * w);
  return {x / n, y / n, z / n, w / n};
}

}  // namespace

void writeGltf(const Scene &scene, const BakedMesh &baked, const ExportProvenance &provenance, const std::string &path,
               const GltfLightmap *lightmap) {
  LightmapTextures lightmapTextures;
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = std::string("Radiant ") + RADIANT_VERSION;
  model.buffers.emplace_back();

  tinygltf::Mesh mesh;
  mesh.name = "radiosity solution";
  std::vector<int> materialIndex(scene.materials.size(), -1);
  bool anyEmissiveStrength = false, anyTransmission = false;
  Vec3 lowest(INFINITY, INFINITY, INFINITY), highest(-INFINITY, -INFINITY, -INFINITY);
  for (const BakedPrimitive &p : baked.primitives) {
    int &material = materialIndex[p.material];
    if (material < 0) {
      model.materials.push_back(gltfMaterial(model, scene, scene.materials[p.material]));
      if (lightmap && !p.lightmapUvs.empty()) {
        if (lightmapTextures.display < 0) lightmapTextures = addLightmapTextures(model, *lightmap);
        lightmapMaterial(model.materials.back(), lightmapTextures);
      }
      material = int(model.materials.size() - 1);
      anyEmissiveStrength |= model.materials.back().extensions.count("KHR_materials_emissive_strength") > 0;
      anyTransmission |= model.materials.back().extensions.count("KHR_materials_transmission") > 0;
    }
    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.material = material;
    primitive.attributes["POSITION"] = addFloatAccessor(model, p.positions, 3, true);
    primitive.attributes["NORMAL"] = addFloatAccessor(model, p.normals, 3, false);
    if (p.hasUv) {
      // glTF's texture space has v down from the image's top edge: t = 1 − v.
      std::vector<float> st(p.uvs);
      for (size_t i = 1; i < st.size(); i += 2) st[i] = 1.0f - st[i];
      primitive.attributes["TEXCOORD_0"] = addFloatAccessor(model, st, 2, false);
    }
    if (!p.lightmapUvs.empty()) {
      const int lightmap = addFloatAccessor(model, p.lightmapUvs, 2, false);
      primitive.attributes["TEXCOORD_1"] = lightmap;
      // glTF numbers a semantic's sets from 0 without gaps (the validator's
      // MESH_PRIMITIVE_INDEXED_SEMANTIC_CONTINUITY): an untextured material's
      // TEXCOORD_0, which nothing reads, is the lightmap's, sharing its data.
      if (!p.hasUv) primitive.attributes["TEXCOORD_0"] = lightmap;
    }
    if (!p.colour.empty()) primitive.attributes["COLOR_0"] = addFloatAccessor(model, p.colour, 3, false);
    if (!p.radiance.empty()) primitive.attributes["_RADIANCE"] = addFloatAccessor(model, p.radiance, 3, false);
    if (!p.irradiance.empty()) primitive.attributes["_IRRADIANCE"] = addFloatAccessor(model, p.irradiance, 3, false);
    primitive.indices = addIndexAccessor(model, p.indices, p.vertexCount());
    mesh.primitives.push_back(primitive);
    const tinygltf::Accessor &positions = model.accessors[size_t(primitive.attributes["POSITION"])];
    lowest = Vec3(std::min(lowest.x, positions.minValues[0]), std::min(lowest.y, positions.minValues[1]),
                  std::min(lowest.z, positions.minValues[2]));
    highest = Vec3(std::max(highest.x, positions.maxValues[0]), std::max(highest.y, positions.maxValues[1]),
                   std::max(highest.z, positions.maxValues[2]));
  }
  model.meshes.push_back(mesh);
  tinygltf::Node meshNode;
  meshNode.name = "radiosity solution";
  meshNode.mesh = 0;
  model.nodes.push_back(meshNode);

  tinygltf::Camera camera;
  camera.name = "camera";
  camera.type = "perspective";
  camera.perspective.yfov = scene.camera.verticalFovDegrees * kPi / 180;
  camera.perspective.aspectRatio = double(scene.render.width) / double(scene.render.height);
  // Clipping planes a thousandth of the scene's size and a hundred times it.
  const double size = baked.primitives.empty() ? 1.0 : std::max(length(highest - lowest), 1e-3);
  camera.perspective.znear = 1e-3 * size;
  camera.perspective.zfar = 1e2 * size;
  model.cameras.push_back(camera);
  tinygltf::Node cameraNode;
  cameraNode.name = "camera";
  cameraNode.camera = 0;
  cameraNode.translation = {scene.camera.eye.x, scene.camera.eye.y, scene.camera.eye.z};
  cameraNode.rotation = cameraRotation(scene.camera);
  model.nodes.push_back(cameraNode);

  tinygltf::Scene gltfScene;
  gltfScene.name = std::filesystem::path(scene.sourceFile).filename().string();
  gltfScene.nodes = {0, 1};
  model.scenes.push_back(gltfScene);
  model.defaultScene = 0;

  model.extensionsUsed = {"KHR_materials_unlit"};
  if (lightmapTextures.display >= 0) model.extensionsUsed.push_back(kLightmapExtension);
  if (anyEmissiveStrength) model.extensionsUsed.push_back("KHR_materials_emissive_strength");
  if (anyTransmission) {
    model.extensionsUsed.push_back("KHR_materials_transmission");
    model.extensionsUsed.push_back("KHR_materials_ior");
  }

  Value::Object tonemap{{"operator", Value(provenance.toneOperator)}, {"adaptedTo", Value(provenance.adaptedTo)}};
  for (const auto &[name, value] : provenance.toneParameters) tonemap[name] = number(value);
  size_t triangles = 0;
  for (const BakedPrimitive &p : baked.primitives) triangles += p.triangleCount();
  model.asset.extras =
      Value(Value::Object{{"radiant", Value(Value::Object{{"version", Value(std::string(RADIANT_VERSION))},
                                                          {"scene", Value(scene.sourceFile)},
                                                          {"solver", Value(provenance.solver)},
                                                          {"elements", Value(int(baked.elements))},
                                                          {"triangles", Value(int(triangles))},
                                                          {"units", Value(std::string("metre"))},
                                                          {"radianceUnit", Value(std::string("W/(sr·m²)"))},
                                                          {"irradianceUnit", Value(std::string("W/m²"))},
                                                          {"luminousEfficacy", number(kLuminousEfficacy)},
                                                          {"tonemap", Value(std::move(tonemap))}})}});
  if (lightmapTextures.display >= 0) {
    Value::Object &radiant = model.asset.extras.Get<Value::Object>()["radiant"].Get<Value::Object>();
    radiant["lightmap"] = Value(Value::Object{{"width", Value(lightmap->width)},
                                              {"height", Value(lightmap->height)},
                                              {"texelSize", number(lightmap->texelSize)},
                                              {"charts", Value(int(lightmap->charts))},
                                              {"utilisation", number(lightmap->utilisation)}});
  }

  const bool binary = std::filesystem::path(path).extension() == ".glb";
  writeAtomically(path, [&](const std::string &temporary) {
    std::ofstream out(temporary, std::ios::binary);
    tinygltf::TinyGLTF writer;
    if (!out || !writer.WriteGltfSceneToStream(&model, out, !binary, binary))
      throw std::runtime_error("cannot write glTF");
    out.close();
    if (!out) throw std::runtime_error("write failed (disk full?)");
  });
}

}  // namespace radiant
