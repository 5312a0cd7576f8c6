// glTF materials as Radiant materials (docs/scene-format.md, "glTF scenes"):
//   extras.radiant (written by radiant export, docs/export.md) → the material
//   exactly; otherwise the metallic-roughness approximation:
//   baseColorFactor × baseColorTexture → diffuse reflectance ρ and its
//   texture (C&W eq. 9.11), emissiveFactor × KHR_materials_emissive_strength
//   → emitted radiance in W·sr⁻¹·m⁻² (glTF gives emission no absolute unit;
//   Radiant reads it as radiance), metallic 1 with roughness 0 → a mirror,
//   KHR_materials_transmission → glass with KHR_materials_ior, anything
//   else → Lambertian with the base colour.

#include <cctype>

#include "scene/gltf_file.h"
#include "scene/load_detail.h"
#include "util/input_file.h"

namespace radiant::gltf {

namespace fs = std::filesystem;

namespace {

/// A number in an extension object of the material, or `fallback`.
double extensionNumber(const JsonNode &material, const char *extension, const char *key, double fallback) {
  if (!material.has("extensions") || !material.child("extensions").has(extension)) return fallback;
  return material.child("extensions").child(extension).number(key, fallback);
}

Bands colour(const JsonNode &node, const char *key, size_t size, double fallback) {
  if (!node.has(key)) return Bands(fallback);
  std::vector<JsonNode> values = node.child(key).asArray(size, size);
  Bands result;
  for (int b = 0; b < kBandCount; ++b) {
    result[b] = values[size_t(b)].asNumber();
    if (result[b] < 0) values[size_t(b)].fail("a colour factor must be ≥ 0");
  }
  return result;
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
  m.transmissionRoughness = radiant.number("transmission_roughness", m.transmissionRoughness);
  m.emission = radiant.bands("emission", m.emission);
}

void setTexture(const GltfFile &file, const JsonNode &info, Material &m, Scene &scene, TextureCache &textures) {
  JsonNode texture = file.entry("textures", info.child("index"));
  if (info.integer("texCoord", 0, 0, INT32_MAX) != 0)
    scene.warnings.push_back(file.path() + ": " + info.path() + ": texCoord " + info.child("texCoord").value().dump() +
                             " is read as TEXCOORD_0 (Radiant reads one set of texture coordinates)");
  if (info.has("extensions") && info.child("extensions").has("KHR_texture_transform"))
    scene.warnings.push_back(file.path() + ": " + info.path() + ": KHR_texture_transform is not read");
  if (!texture.has("source")) texture.fail("a texture without a source image");
  JsonNode image = file.entry("images", texture.child("source"));
  const size_t imageIndex = size_t(texture.child("source").asInteger(0, INT32_MAX));
  TextureWrap wrap = TextureWrap::Repeat;
  if (texture.has("sampler")) {
    JsonNode sampler = file.entry("samplers", texture.child("sampler"));
    const int64_t wrapS = sampler.integer("wrapS", 10497, 0, INT32_MAX),
                  wrapT = sampler.integer("wrapT", 10497, 0, INT32_MAX);
    if (wrapS == 33648 || wrapT == 33648)
      scene.warnings.push_back(file.path() + ": " + sampler.path() +
                               ": MIRRORED_REPEAT is read as REPEAT (Radiant repeats or clamps)");
    if (wrapS != wrapT)
      scene.warnings.push_back(file.path() + ": " + sampler.path() +
                               ": wrapS and wrapT differ; Radiant wraps both as wrapS says");
    m.textureWrap = wrapS == 33071 ? TextureWrap::Clamp : TextureWrap::Repeat;
    wrap = m.textureWrap;
  }
  m.diffuseTextureFrom = image.location();
  if (image.has("uri") && image.child("uri").asString().rfind("data:", 0) != 0) {
    // An image file beside the glTF: loaded with the scene's other textures.
    const std::string uri = image.child("uri").asString();
    const fs::path imageFile = file.directory() / decodeUri(uri);
    if (const InputFileRead read = checkInputFile(imageFile.string()); !read.ok())
      image.child("uri").fail(inputFileProblem(read, "image '" + imageFile.string() + "'"));
    m.diffuseTexture = imageFile.lexically_normal().string();
    m.diffuseTextureFrom = image.child("uri").location();
    return;
  }
  // Embedded (a buffer view or a data: URI): decoded here, once per wrap mode.
  m.diffuseTexture = file.path() + " " + image.path();
  const auto key = std::make_pair(imageIndex, wrap);
  if (auto it = textures.find(key); it != textures.end()) {
    m.diffuseTextureIndex = it->second;
    return;
  }
  const std::vector<unsigned char> &bytes = file.imageBytes(imageIndex, image);
  scene.textures.push_back(Texture::decode(bytes, image.location(), TextureEncoding::Colour, wrap));
  m.diffuseTextureIndex = textures[key] = int(scene.textures.size()) - 1;
}

}  // namespace

Material convertMaterial(const GltfFile &file, const JsonNode &node, Scene &scene, TextureCache &textures) {
  Material m;
  m.definedAt = node.location();
  detail::MaterialFieldNames names{"baseColorFactor", "baseColorFactor", "emissiveFactor × emissiveStrength",
                                   "KHR_materials_ior ior", "roughnessFactor"};
  const JsonNode pbr = node.has("pbrMetallicRoughness") ? node.child("pbrMetallicRoughness")
                                                        : file.emptyObject(node.path() + "/pbrMetallicRoughness");
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
    names.transmissionRoughness = "extras.radiant.transmission_roughness";
  }
  if (textured) setTexture(file, pbr.child("baseColorTexture"), m, scene, textures);
  if (node.has("emissiveTexture")) {
    scene.warnings.push_back(file.path() + ": " + node.path() +
                             ": emissiveTexture is not read (emission is uniform: emissiveFactor × strength)");
  }
  detail::checkMaterial(m, m.definedAt, names);
  return m;
}

}  // namespace radiant::gltf
