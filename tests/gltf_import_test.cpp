// glTF 2.0 scenes and models (src/scene/load_gltf.cpp): small files written
// here by hand — the JSON, with one buffer as a data: URI (.gltf) or a BIN
// chunk (.glb) — and what the loader makes of them: positions after the node
// transforms, winding, normals and texture coordinates, materials, textures,
// the camera, and each refusal at its file and JSON path.

#include <gtest/gtest.h>
#include <stb/stb_image_write.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "input_errors.h"
#include "scene/load_scene.h"
#include "temp_dir.h"
#include "util/error.h"

namespace radiant {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

std::string base64(const std::vector<unsigned char> &bytes) {
  static const char *kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = uint32_t(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= uint32_t(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) v |= bytes[i + 2];
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[v & 63] : '=';
  }
  return out;
}

/// A glTF document with one buffer, built by appending accessors.
struct Gltf {
  Json doc = {{"asset", {{"version", "2.0"}}}};
  std::vector<unsigned char> bin;

  /// A tightly packed accessor over a new buffer view; returns its index.
  template <typename T>
  int accessor(const std::vector<T> &values, const char *type, int componentType) {
    while (bin.size() % 4) bin.push_back(0);
    const size_t offset = bin.size();
    bin.resize(offset + values.size() * sizeof(T));
    std::memcpy(bin.data() + offset, values.data(), values.size() * sizeof(T));
    const int components = std::string(type) == "SCALAR" ? 1 : type[3] - '0';
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * sizeof(T)}});
    doc["accessors"].push_back({{"bufferView", doc["bufferViews"].size() - 1},
                                {"componentType", componentType},
                                {"count", values.size() / size_t(components)},
                                {"type", type}});
    return int(doc["accessors"].size()) - 1;
  }
  int positions(const std::vector<float> &xyz) { return accessor(xyz, "VEC3", 5126); }
  /// Bytes (an image) in a buffer view of their own.
  int bufferView(const std::vector<unsigned char> &bytes) {
    while (bin.size() % 4) bin.push_back(0);
    const size_t offset = bin.size();
    bin.insert(bin.end(), bytes.begin(), bytes.end());
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes.size()}});
    return int(doc["bufferViews"].size()) - 1;
  }
  /// A mesh of one primitive; returns the mesh index.
  int mesh(Json primitive, const std::string &name = "") {
    Json mesh = {{"primitives", Json::array({primitive})}};
    if (!name.empty()) mesh["name"] = name;
    doc["meshes"].push_back(mesh);
    return int(doc["meshes"].size()) - 1;
  }
  int node(Json node) {
    doc["nodes"].push_back(node);
    return int(doc["nodes"].size()) - 1;
  }
  void scene(std::vector<int> roots) { doc["scenes"] = Json::array({{{"nodes", roots}}}), doc["scene"] = 0; }

  std::string gltf() const {
    Json out = doc;
    if (!bin.empty())
      out["buffers"] =
          Json::array({{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
    return out.dump(1);
  }
  std::string glb() const {
    Json out = doc;
    if (!bin.empty()) out["buffers"] = Json::array({{{"byteLength", bin.size()}}});
    std::string json = out.dump();
    while (json.size() % 4) json += ' ';
    std::string chunk(bin.begin(), bin.end());
    while (chunk.size() % 4) chunk += '\0';
    std::string file;
    auto word = [&](uint32_t v) { file.append(reinterpret_cast<const char *>(&v), 4); };
    file = "glTF";
    word(2);
    word(uint32_t(12 + 8 + json.size() + (chunk.empty() ? 0 : 8 + chunk.size())));
    word(uint32_t(json.size()));
    word(0x4E4F534A);
    file += json;
    if (!chunk.empty()) {
      word(uint32_t(chunk.size()));
      word(0x004E4942);
      file += chunk;
    }
    return file;
  }
};

/// The triangle (0,0,0), (1,0,0), (0,1,0): front +z.
Gltf oneTriangle(Json primitiveExtras = Json::object()) {
  Gltf g;
  Json primitive = {{"attributes", {{"POSITION", g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0})}}}};
  primitive.update(primitiveExtras);
  g.mesh(primitive, "tri");
  return g;
}

void expectNear(const Vec3 &a, const Vec3 &b, double tolerance = 1e-9) {
  EXPECT_NEAR(a.x, b.x, tolerance) << "y " << a.y << " z " << a.z;
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

void expectBands(const Bands &a, const Bands &b, double tolerance = 1e-9) {
  for (int k = 0; k < kBandCount; ++k) EXPECT_NEAR(a[k], b[k], tolerance) << "band " << k;
}

const Face &onlyFaceOf(const Scene &scene, uint32_t object) {
  for (const Face &f : scene.faces)
    if (f.object == object) return f;
  throw std::runtime_error("object has no face");
}

TEST(GltfImport, NestedTrsAndMatrixTransformsPlaceEachInstance) {
  Gltf g = oneTriangle();
  const double s = std::sqrt(0.5);
  // Parent: translate (1, 2, 3) · scale 2; child: 90° about +z, holding the mesh.
  const int child = g.node({{"name", "turned"}, {"mesh", 0}, {"rotation", {0, 0, s, s}}});
  const int parent = g.node({{"children", {child}}, {"translation", {1, 2, 3}}, {"scale", {2, 2, 2}}});
  // The same mesh again, by a column-major matrix translating by (10, 0, 0).
  const int moved = g.node({{"mesh", 0}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 10, 0, 0, 1}}});
  g.scene({parent, moved});
  test::TempDir dir("gltf");
  Scene scene = loadScene(dir.write("model.gltf", g.gltf()));
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.objects[0].name, "model/turned");
  EXPECT_EQ(scene.objects[1].name, "model/tri");  // no node name: the mesh's
  ASSERT_EQ(scene.faces.size(), 2u);
  const Face &turned = onlyFaceOf(scene, 0);
  // (1,0,0) → rotated (0,1,0) → scaled (0,2,0) → translated (1,4,3).
  expectNear(scene.positions[turned.vertices[0]], {1, 2, 3});
  expectNear(scene.positions[turned.vertices[1]], {1, 4, 3});
  expectNear(scene.positions[turned.vertices[2]], {-1, 2, 3});
  const Face &instance = onlyFaceOf(scene, 1);
  expectNear(scene.positions[instance.vertices[1]], {11, 0, 0});
  expectNear(scene.faceNormal(turned), {0, 0, 1});
}

TEST(GltfImport, MirroringNodeKeepsTheFrontAndNormalsTransform) {
  Gltf g;
  const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int n = g.positions({0, 0, 1, 0, 0, 1, 0, 0, 1});
  const int uv = g.accessor(std::vector<float>{0, 0, 1, 0.25f, 0, 1}, "VEC2", 5126);
  g.mesh({{"attributes", {{"POSITION", p}, {"NORMAL", n}, {"TEXCOORD_0", uv}}}});
  g.scene({g.node({{"mesh", 0}, {"scale", {-1, 1, 1}}}), g.node({{"mesh", 0}, {"translation", {0, 0, 5}}})});
  test::TempDir dir("gltf");
  Scene scene = loadScene(dir.write("m.gltf", g.gltf()));
  ASSERT_EQ(scene.faces.size(), 2u);
  for (const Face &f : scene.faces) {
    SCOPED_TRACE(f.object);
    expectNear(scene.faceNormal(f), {0, 0, 1});  // mirrored, but the winding is reversed: the front stays +z
    for (int k = 0; k < 3; ++k) {
      ASSERT_GE(f.normals[k], 0);
      expectNear(scene.normals[size_t(f.normals[k])], {0, 0, 1});
    }
  }
  // TEXCOORD_0 (1, 0.25) is v = 0.75 in Radiant's convention (v up).
  const Face &plain = onlyFaceOf(scene, 1);
  ASSERT_GE(plain.uvs[1], 0);
  EXPECT_DOUBLE_EQ(scene.uvs[2 * size_t(plain.uvs[1])], 1.0);
  EXPECT_DOUBLE_EQ(scene.uvs[2 * size_t(plain.uvs[1]) + 1], 0.75);
}

TEST(GltfImport, StripsFansAndIndexTypesMakeTheSameSquare) {
  // The unit square two ways, each front +z, with indices of each integer type.
  const std::vector<float> square = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  Gltf g;
  const int p = g.positions(square);
  const int strip = g.accessor(std::vector<uint8_t>{0, 1, 2, 3}, "SCALAR", 5121);
  const int fan = g.accessor(std::vector<uint32_t>{0, 1, 3, 2}, "SCALAR", 5125);
  const int list = g.accessor(std::vector<uint16_t>{0, 1, 3, 0, 3, 2}, "SCALAR", 5123);
  g.mesh({{"attributes", {{"POSITION", p}}}, {"indices", strip}, {"mode", 5}});
  g.mesh({{"attributes", {{"POSITION", p}}}, {"indices", fan}, {"mode", 6}});
  g.mesh({{"attributes", {{"POSITION", p}}}, {"indices", list}});
  g.scene({g.node({{"mesh", 0}}), g.node({{"mesh", 1}, {"translation", {0, 0, 1}}}),
           g.node({{"mesh", 2}, {"translation", {0, 0, 2}}})});
  test::TempDir dir("gltf");
  Scene scene = loadScene(dir.write("m.gltf", g.gltf()));
  ASSERT_EQ(scene.faces.size(), 6u);
  double area[3] = {0, 0, 0};
  for (const Face &f : scene.faces) {
    expectNear(scene.faceNormal(f), {0, 0, 1});
    area[f.object] += scene.faceArea(f);
  }
  for (double a : area) EXPECT_NEAR(a, 1.0, 1e-12);
}

TEST(GltfImport, QuantisedPositionsAreRead) {
  Gltf g;
  // KHR_mesh_quantization: normalized unsigned shorts, scaled by the node.
  const int p = g.accessor(std::vector<uint16_t>{0, 0, 0, 65535, 0, 0, 0, 65535, 0}, "VEC3", 5123);
  g.doc["accessors"][size_t(p)]["normalized"] = true;
  g.mesh({{"attributes", {{"POSITION", p}}}});
  g.scene({g.node({{"mesh", 0}, {"scale", {2, 2, 2}}})});
  test::TempDir dir("gltf");
  Scene scene = loadScene(dir.write("q.gltf", g.gltf()));
  ASSERT_EQ(scene.faces.size(), 1u);
  expectNear(scene.positions[scene.faces[0].vertices[1]], {2, 0, 0});
}

TEST(GltfImport, DegenerateTrianglesAreDropped) {
  Gltf g;
  g.mesh({{"attributes", {{"POSITION", g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 2, 0, 0})}}}});
  g.scene({g.node({{"mesh", 0}})});
  test::TempDir dir("gltf");
  Scene scene = loadScene(dir.write("d.gltf", g.gltf()));
  EXPECT_EQ(scene.faces.size(), 1u);
  EXPECT_EQ(scene.droppedDegenerateFaces, 1u);
}

/// One triangle per material, materials given as JSON.
Scene loadMaterials(const test::TempDir &dir, const std::vector<Json> &materials) {
  Gltf g;
  const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  std::vector<int> roots;
  for (size_t i = 0; i < materials.size(); ++i) {
    g.doc["materials"].push_back(materials[i]);
    g.mesh({{"attributes", {{"POSITION", p}}}, {"material", i}});
    roots.push_back(g.node({{"mesh", i}, {"translation", {0, 0, double(i)}}}));
  }
  g.scene(roots);
  return loadScene(dir.write("materials.gltf", g.gltf()));
}

const Material &materialOf(const Scene &scene, uint32_t object) {
  return scene.materials[onlyFaceOf(scene, object).material];
}

TEST(GltfImport, MaterialsFromMetallicRoughness) {
  test::TempDir dir("gltf");
  Scene scene = loadMaterials(
      dir,
      {
          {{"name", "red"},
           {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 0.125, 1}}, {"metallicFactor", 0}}}},
          {{"name", "lamp"},
           {"emissiveFactor", {1, 0.5, 0}},
           {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 10}}}}}},
          {{"name", "chrome"},
           {"pbrMetallicRoughness",
            {{"baseColorFactor", {0.9, 0.8, 0.7, 1}}, {"metallicFactor", 1}, {"roughnessFactor", 0}}}},
          {{"name", "glass"},
           {"extensions",
            {{"KHR_materials_transmission", {{"transmissionFactor", 1}}}, {"KHR_materials_ior", {{"ior", 1.33}}}}}},
          Json::object(),
      });
  const Material &red = materialOf(scene, 0);
  EXPECT_EQ(red.name, "red");
  EXPECT_EQ(red.kind, MaterialKind::Lambertian);
  expectBands(red.diffuse, Bands(0.5, 0.25, 0.125));
  const Material &lamp = materialOf(scene, 1);
  expectBands(lamp.emission, Bands(10, 5, 0));               // emissiveFactor × strength, read as W·sr⁻¹·m⁻²
  expectBands(lamp.diffuse, Bands(kMaxDiffuseReflectance));  // glTF's default white, just below 1
  const Material &chrome = materialOf(scene, 2);
  EXPECT_EQ(chrome.kind, MaterialKind::Mirror);
  expectBands(chrome.specular, Bands(0.9, 0.8, 0.7));
  const Material &glass = materialOf(scene, 3);
  EXPECT_EQ(glass.kind, MaterialKind::Dielectric);
  EXPECT_DOUBLE_EQ(glass.ior, 1.33);
  EXPECT_EQ(materialOf(scene, 4).name, "material-4");
}

TEST(GltfImport, RadiantExtrasWinOverThePbrApproximation) {
  test::TempDir dir("gltf");
  Scene scene = loadMaterials(dir, {{{"name", "plastic"},
                                     {"pbrMetallicRoughness", {{"baseColorFactor", {0.1, 0.1, 0.1, 1}}}},
                                     {"emissiveFactor", {1, 1, 1}},
                                     {"extras",
                                      {{"radiant",
                                        {{"kind", "glossy"},
                                         {"diffuse", {0.5, 0.1, 0.1}},
                                         {"specular", {0.2, 0.2, 0.2}},
                                         {"roughness", 0.15},
                                         {"emission", {0, 0, 0}}}}}}}});
  const Material &m = materialOf(scene, 0);
  EXPECT_EQ(m.kind, MaterialKind::Glossy);
  expectBands(m.diffuse, Bands(0.5, 0.1, 0.1));
  expectBands(m.specular, Bands(0.2));
  EXPECT_DOUBLE_EQ(m.roughness, 0.15);
  EXPECT_FALSE(m.isEmitter());
}

std::vector<unsigned char> pngBytes(int width, int height, const std::vector<unsigned char> &rgb) {
  std::vector<unsigned char> out;
  auto append = [](void *context, void *data, int size) {
    auto *bytes = static_cast<std::vector<unsigned char> *>(context);
    bytes->insert(bytes->end(), static_cast<unsigned char *>(data), static_cast<unsigned char *>(data) + size);
  };
  stbi_write_png_to_func(append, &out, width, height, 3, rgb.data(), width * 3);
  return out;
}

/// A textured triangle: base colour factor 0.5 times a 2 × 1 image (left 255
/// white, right 0 black), its image stored as `how`: "bufferView", "data" or "file".
Gltf texturedTriangle(const test::TempDir &dir, const std::string &how, int wrap) {
  Gltf g;
  const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int uv = g.accessor(std::vector<float>{0, 0, 1, 0, 0, 1}, "VEC2", 5126);
  g.doc["materials"].push_back(
      {{"name", "textured"},
       {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}, {"baseColorTexture", {{"index", 0}}}}}});
  const std::vector<unsigned char> png = pngBytes(2, 1, {255, 255, 255, 0, 0, 0});
  if (how == "bufferView")
    g.doc["images"].push_back({{"bufferView", g.bufferView(png)}, {"mimeType", "image/png"}});
  else if (how == "data")
    g.doc["images"].push_back({{"uri", "data:image/png;base64," + base64(png)}});
  else
    g.doc["images"].push_back({{"uri", "my%20texture.png"}}),
        dir.write("my texture.png", std::string(png.begin(), png.end()));
  g.doc["samplers"].push_back({{"wrapS", wrap}, {"wrapT", wrap}});
  g.doc["textures"].push_back({{"source", 0}, {"sampler", 0}});
  g.mesh({{"attributes", {{"POSITION", p}, {"TEXCOORD_0", uv}}}, {"material", 0}});
  g.scene({g.node({{"mesh", 0}})});
  return g;
}

TEST(GltfImport, BaseColourTexturesEmbeddedOrBesideTheFile) {
  test::TempDir dir("gltf");
  for (const char *how : {"bufferView", "data", "file"}) {
    SCOPED_TRACE(how);
    const Gltf g = texturedTriangle(dir, how, 33071);
    for (bool binary : {false, true}) {
      Scene scene = loadScene(binary ? dir.write("t.glb", g.glb()) : dir.write("t.gltf", g.gltf()));
      ASSERT_EQ(scene.materials.size(), 1u);
      const Material &m = scene.materials[0];
      expectBands(m.diffuse, Bands(0.5));
      ASSERT_GE(m.diffuseTextureIndex, 0);
      EXPECT_EQ(m.textureWrap, TextureWrap::Clamp);
      const Texture &t = scene.textures[size_t(m.diffuseTextureIndex)];
      EXPECT_EQ(t.width(), 2);
      EXPECT_EQ(t.wrap(), TextureWrap::Clamp);
      expectBands(t.bilinear(0.25, 0.5), Bands(1.0), 1e-6);  // sRGB 255 decodes to 1
      expectBands(t.bilinear(0.75, 0.5), Bands(0.0), 1e-6);
    }
  }
  // MIRRORED_REPEAT is read as REPEAT, with a warning.
  Scene mirrored = loadScene(dir.write("r.gltf", texturedTriangle(dir, "data", 33648).gltf()));
  EXPECT_EQ(mirrored.materials[0].textureWrap, TextureWrap::Repeat);
  bool warned = false;
  for (const std::string &w : mirrored.warnings) warned |= w.find("MIRRORED_REPEAT") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(GltfImport, TheFirstPerspectiveCameraIsTheView) {
  Gltf g = oneTriangle();
  g.doc["cameras"] =
      Json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"aspectRatio", 2.0}, {"znear", 0.1}}}},
                   {{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}}});
  const double s = std::sqrt(0.5);
  // Node 1 holds camera 0 turned 90° about +y: it looks down −x from (0, 1, 5).
  const int mesh = g.node({{"mesh", 0}});
  const int camera = g.node({{"camera", 0}, {"rotation", {0, s, 0, s}}, {"translation", {0, 1, 5}}});
  const int other = g.node({{"camera", 1}});
  g.scene({other, mesh, camera});
  test::TempDir dir("gltf");
  Scene scene = loadScene(dir.write("c.glb", g.glb()));
  expectNear(scene.camera.eye, {0, 1, 5});
  expectNear(normalize(scene.camera.target - scene.camera.eye), {-1, 0, 0});
  expectNear(scene.camera.up, {0, 1, 0});
  EXPECT_NEAR(scene.camera.verticalFovDegrees, 0.5 * 180 / kPi, 1e-9);
  EXPECT_EQ(scene.render.width, 512);
  EXPECT_EQ(scene.render.height, 256);
}

TEST(GltfImport, WithoutACameraTheBoundsAreFramed) {
  Gltf g = oneTriangle();
  g.scene({g.node({{"mesh", 0}})});
  test::TempDir dir("gltf");
  Scene scene = loadScene(dir.write("n.gltf", g.gltf()));
  EXPECT_NEAR(scene.camera.target.x, 0.5, 1e-12);
  EXPECT_GT(scene.camera.eye.z, 1.0);
  EXPECT_DOUBLE_EQ(scene.camera.verticalFovDegrees, 40.0);
}

TEST(GltfImport, GlbAndGltfGiveTheSameScene) {
  Gltf g = oneTriangle({{"material", 0}});
  g.doc["materials"].push_back(
      {{"pbrMetallicRoughness", {{"baseColorFactor", {0.3, 0.4, 0.5, 1}}}}, {"emissiveFactor", {1, 1, 1}}});
  g.scene({g.node({{"mesh", 0}, {"translation", {1, 2, 3}}})});
  test::TempDir dir("gltf");
  Scene text = loadScene(dir.write("same.gltf", g.gltf()));
  Scene binary = loadScene(dir.write("same.glb", g.glb()));
  ASSERT_EQ(text.positions.size(), binary.positions.size());
  for (size_t i = 0; i < text.positions.size(); ++i) EXPECT_EQ(text.positions[i], binary.positions[i]);
  ASSERT_EQ(text.faces.size(), binary.faces.size());
  ASSERT_EQ(text.materials.size(), binary.materials.size());
  expectBands(text.materials[0].diffuse, binary.materials[0].diffuse, 0);
  expectBands(text.materials[0].emission, binary.materials[0].emission, 0);
}

TEST(GltfImport, AJsonSceneObjectPlacesTheModelAndOverridesMaterials) {
  Gltf g = oneTriangle({{"material", 0}});
  g.mesh({{"attributes", {{"POSITION", 0}}}}, "bare");  // no material: the entry's
  g.doc["materials"].push_back(
      {{"name", "paint"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.1, 0.2, 0.3, 1}}}}});
  g.scene({g.node({{"name", "a"}, {"mesh", 0}}), g.node({{"name", "b"}, {"mesh", 1}, {"translation", {0, 0, 1}}})});
  test::TempDir dir("gltf");
  dir.write("model.glb", g.glb());
  const std::string scenePath = dir.write("scene.json", R"({
    "units": "cm",
    "materials": {"paint": {"reflectance": 0.7, "emission": 1}, "grey": {"reflectance": 0.3}},
    "objects": [{"name": "thing", "type": "gltf", "file": "model.glb", "material": "grey",
                 "transform": {"scale": 100, "translate": [0, 0, 50]}}]})");
  Scene scene = loadScene(scenePath);
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.objects[0].name, "thing/a");
  EXPECT_EQ(scene.objects[1].name, "thing/b");
  // 1 m scaled by 100, in centimetres: 1 m; translated by 50 cm.
  expectNear(scene.positions[onlyFaceOf(scene, 0).vertices[1]], {1, 0, 0.5});
  EXPECT_EQ(materialOf(scene, 0).name, "paint");  // the JSON material of the same name wins
  expectBands(materialOf(scene, 0).diffuse, Bands(0.7));
  EXPECT_EQ(materialOf(scene, 1).name, "grey");
}

/// Error messages: file, JSON path, what is wrong.
struct Refusal {
  std::string what;
  std::function<void(Gltf &)> spoil;
  std::string path, message;
};

/// Each refusal's spoiled one-triangle scene written as bad.gltf and as bad.glb, and `check`ed.
void forEachSpoiledFile(const std::vector<Refusal> &refusals, const test::TempDir &dir,
                        const std::function<void(const Refusal &, const std::string &)> &check) {
  for (const Refusal &refusal : refusals) {
    SCOPED_TRACE(refusal.what);
    Gltf g = oneTriangle();
    g.scene({g.node({{"mesh", 0}})});
    refusal.spoil(g);
    for (const char *name : {"bad.gltf", "bad.glb"})
      check(refusal, dir.write(name, std::string(name).ends_with("glb") ? g.glb() : g.gltf()));
  }
}

TEST(GltfImportErrors, EachRefusalNamesTheFileAndJsonPath) {
  const std::vector<Refusal> refusals = {
      {"points", [](Gltf &g) { g.doc["meshes"][0]["primitives"][0]["mode"] = 0; }, "/meshes/0/primitives/0/mode",
       "mode 0 (points)"},
      {"count past the buffer view", [](Gltf &g) { g.doc["accessors"][0]["count"] = 10; }, "/accessors/0",
       "count 10 exceeds buffer view 0"},
      {"no such accessor", [](Gltf &g) { g.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 7; },
       "/meshes/0/primitives/0/attributes/POSITION", "accessors 7 does not exist (the file has 1)"},
      {"buffer view past its buffer", [](Gltf &g) { g.doc["bufferViews"][0]["byteLength"] = 1000000; },
       "/bufferViews/0", "of buffer 0, which has 36 bytes"},
      {"integer positions as a matrix", [](Gltf &g) { g.doc["accessors"][0]["type"] = "MAT3"; }, "/accessors/0/type",
       "type MAT3 is not read"},
      {"a node that is its own child", [](Gltf &g) { g.doc["nodes"][0]["children"] = {0}; }, "/nodes/0/children/0",
       "node 0 is reached a second time"},
      {"draco", [](Gltf &g) { g.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"}; }, "/extensionsRequired/0",
       "requires the extension KHR_draco_mesh_compression"},
      {"index out of range",
       [](Gltf &g) {
         g.doc["meshes"][0]["primitives"][0]["indices"] = g.accessor(std::vector<uint16_t>{0, 1, 9}, "SCALAR", 5123);
       },
       "/accessors/1", "index 9 (element 2) is out of range"},
      {"no such material", [](Gltf &g) { g.doc["meshes"][0]["primitives"][0]["material"] = 3; },
       "/meshes/0/primitives/0/material", "materials 3 does not exist"},
  };
  test::TempDir dir("gltf");
  forEachSpoiledFile(refusals, dir, [](const Refusal &refusal, const std::string &path) {
    try {
      loadScene(path);
      ADD_FAILURE() << "no error for " << path;
    } catch (const InputError &e) {
      EXPECT_EQ(e.location().file, path);
      EXPECT_EQ(e.location().jsonPath, refusal.path) << e.what();
      EXPECT_NE(std::string(e.what()).find(refusal.message), std::string::npos) << e.what();
    }
  });
}

TEST(GltfImportErrors, WhatTinygltfWouldRefuseIsRefusedFirstAtItsJsonPath) {
  // tinygltf refuses these too, in words of its own and with no position
  // ("'count' property is not a positive integer"); gltf_schema.cpp checks
  // them first (issue 38: 177 of tools/error_corpus.py's glTF refusals named no path).
  const std::vector<Refusal> refusals = {
      {"a count that is a string", [](Gltf &g) { g.doc["accessors"][0]["count"] = "3"; }, "/accessors/0/count",
       "expected an integer"},
      {"an unknown component type", [](Gltf &g) { g.doc["accessors"][0]["componentType"] = 5000; },
       "/accessors/0/componentType", "componentType 5000 is not one of glTF's"},
      {"an unknown accessor type", [](Gltf &g) { g.doc["accessors"][0]["type"] = "VEC"; }, "/accessors/0/type",
       "type \"VEC\" is not one of SCALAR"},
      {"an emissive factor of two numbers",
       [](Gltf &g) {
         g.doc["materials"] = Json::array({{{"emissiveFactor", {1, 1}}}});
         g.doc["meshes"][0]["primitives"][0]["material"] = 0;
       },
       "/materials/0/emissiveFactor", "expected"},
      {"a misspelt camera type",
       [](Gltf &g) {
         g.doc["cameras"] = Json::array({{{"type", "perspectiv"}}});
       },
       "/cameras/0/type", "camera type \"perspectiv\" is neither"},
      {"indices without a buffer view",
       [](Gltf &g) {
         g.doc["meshes"][0]["primitives"][0]["indices"] = g.accessor(std::vector<uint16_t>{0, 1, 2}, "SCALAR", 5123);
         g.doc["accessors"][1].erase("bufferView");
       },
       "/accessors/1", "the accessor of a primitive's indices needs a bufferView"},
      {"primitives that are not an array", [](Gltf &g) { g.doc["meshes"][0]["primitives"] = 1; },
       "/meshes/0/primitives", "expected an array"},
  };
  test::TempDir dir("gltf");
  forEachSpoiledFile(refusals, dir, [](const Refusal &refusal, const std::string &path) {
    const std::string error = test::loadErrorOf(path);
    EXPECT_NE(error.find(path + ": at " + refusal.path + ": "), std::string::npos) << error;
    EXPECT_NE(error.find(refusal.message), std::string::npos) << error;
  });
  // A .gltf file's buffer without a uri (only a GLB's first buffer is its BIN chunk).
  Gltf g = oneTriangle();
  g.scene({g.node({{"mesh", 0}})});
  Json text = Json::parse(g.gltf());
  text["buffers"][0].erase("uri");
  const std::string path = dir.write("no-uri.gltf", text.dump());
  EXPECT_NE(test::loadErrorOf(path).find(path + ": at /buffers/0: a buffer of a .gltf file needs a \"uri\""),
            std::string::npos)
      << test::loadErrorOf(path);
}

TEST(GltfImportErrors, GltfOneIsNamedAsSuchWithTheFile) {
  // glTF 1.0 (CesiumMilkTruck) writes its version as the number 1 or as "1.0"; it was refused with
  // "at /asset/version: expected a string, got the number 1" (issue 38).
  test::TempDir dir("gltf");
  for (const std::string version : {"1", "1.0", "\"1.0\"", "\"1.1\""}) {
    const std::string path = dir.write("truck.gltf", R"({"asset": {"version": )" + version + R"(}, "scenes": []})");
    const std::string error = test::loadErrorOf(path);
    EXPECT_NE(error.find(path + ": at /asset/version: '" + path + "' is a glTF 1.0 file (" + version +
                         "), which Radiant does not read: it reads glTF 2.0"),
              std::string::npos)
        << error;
  }
  const std::string three = dir.write("three.gltf", R"({"asset": {"version": "3.0"}})");
  EXPECT_NE(test::loadErrorOf(three).find("is glTF version 3.0, which Radiant does not read: it reads glTF 2.0"),
            std::string::npos);
  std::string glb("glTF\x01\0\0\0\x14\0\0\0\0\0\0\0JSON", 20);
  const std::string binary = dir.write("old.glb", glb);
  EXPECT_NE(test::loadErrorOf(binary).find("is a GLB of version 1 (glTF 1.0), which Radiant does not read"),
            std::string::npos)
      << test::loadErrorOf(binary);
}

TEST(GltfImportErrors, MissingFilesAreNamedWhereTheyAreReferenced) {
  test::TempDir dir("gltf");
  EXPECT_NE(test::loadErrorOf(dir.file("absent.glb")).find("cannot open glTF file"), std::string::npos);
  const std::string scene = dir.write("scene.json", R"({"objects": [{"type": "gltf", "file": "absent.gltf"}]})");
  try {
    loadScene(scene);
    ADD_FAILURE();
  } catch (const InputError &e) {
    EXPECT_EQ(e.location().file, scene);
    EXPECT_EQ(e.location().jsonPath, "/objects/0/file");
  }
  // A .bin beside the .gltf that is not there.
  Gltf g = oneTriangle();
  g.scene({g.node({{"mesh", 0}})});
  Json doc = nlohmann::ordered_json::parse(g.gltf());
  doc["buffers"][0]["uri"] = "missing.bin";
  const std::string error = test::loadErrorOf(dir.write("nobin.gltf", doc.dump()));
  EXPECT_NE(error.find("nobin.gltf"), std::string::npos) << error;
  EXPECT_NE(error.find("missing.bin"), std::string::npos) << error;
  // An image file that is not there, at the image's uri.
  Json textured = nlohmann::ordered_json::parse(texturedTriangle(dir, "data", 10497).gltf());
  textured["images"][0]["uri"] = "gone.png";
  const std::string imageError = test::loadErrorOf(dir.write("noimage.gltf", textured.dump()));
  EXPECT_NE(imageError.find("noimage.gltf: at /images/0/uri: cannot open image"), std::string::npos) << imageError;
}

TEST(GltfImportErrors, LyingSizesAreRefusedBeforeAllocating) {
  test::TempDir dir("gltf");
  // A GLB whose header claims more bytes than the file has.
  Gltf g = oneTriangle();
  g.scene({g.node({{"mesh", 0}})});
  std::string glb = g.glb();
  const uint32_t huge = 0x7FFFFFFF;
  std::memcpy(glb.data() + 8, &huge, 4);
  EXPECT_NE(test::loadErrorOf(dir.write("long.glb", glb)).find("the GLB header says"), std::string::npos);
  // A mesh whose accessor claims 2^40 vertices, placed by three nodes: refused by the count, not by memory.
  Gltf many = oneTriangle();
  many.doc["accessors"][0]["count"] = uint64_t(1) << 40;
  std::vector<int> roots;
  for (int i = 0; i < 3; ++i) roots.push_back(many.node({{"mesh", 0}}));
  many.scene(roots);
  const std::string error = test::loadErrorOf(dir.write("many.gltf", many.gltf()));
  EXPECT_NE(error.find("Radiant reads at most"), std::string::npos) << error;
}

}  // namespace
}  // namespace radiant
