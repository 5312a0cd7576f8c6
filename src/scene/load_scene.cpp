// JSON scene files (docs/scene-format.md) and bare OBJ files.
//
// Every key is checked: an unknown key, or a key that does not apply to the
// material or object type it is in, is an error with a suggestion.
// Values are checked where they are read, so the error names the JSON path;
// validateScene repeats the value checks on the finished scene so that a bare
// OBJ (or a scene built in code) meets the same rules.
//
// Order matters for one promise: image size, sample count and camera are read
// and checked before any geometry is built, so an absurd size fails before any
// allocation.

#include "scene/load_scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "scene/json_reader.h"
#include "scene/load_detail.h"
#include "scene/mgf_detail.h"
#include "util/file_extension.h"
#include "util/input_file.h"
#include "util/phase.h"

namespace radiant {

namespace fs = std::filesystem;

namespace {

struct UnitName {
  const char *name;
  double metres;
};
constexpr UnitName kUnits[] = {
    {"metres", 1.0},       {"meters", 1.0},       {"m", 1.0},
    {"centimetres", 0.01}, {"centimeters", 0.01}, {"cm", 0.01},
    {"millimetres", 1e-3}, {"millimeters", 1e-3}, {"mm", 1e-3},
    {"inches", 0.0254},    {"in", 0.0254},        {"feet", 0.3048},
    {"ft", 0.3048},
};

double parseUnits(const JsonNode &node) {
  std::string units = node.asString();
  std::vector<std::string> names;
  for (const UnitName &u : kUnits) {
    if (units == u.name) return u.metres;
    names.push_back(u.name);
  }
  node.fail("unknown units '" + units + "'" + didYouMean(units, names) +
            " (expected metres, centimetres, millimetres, inches or feet)");
}

/// Fails on an unknown key, or on a key of another type, with a suggestion.
void checkTypedKeys(const JsonNode &node, const std::vector<std::string> &common,
                    const std::map<std::string, std::vector<std::string>> &perType, const std::string &type,
                    const char *what) {
  std::vector<std::string> all = common;
  for (const auto &[t, keys] : perType) all.insert(all.end(), keys.begin(), keys.end());
  node.checkKeys(all);
  std::vector<std::string> allowed = common;
  const std::vector<std::string> &own = perType.at(type);
  allowed.insert(allowed.end(), own.begin(), own.end());
  for (auto it = node.value().begin(); it != node.value().end(); ++it) {
    const std::string &key = it.key();
    if (key == "comment" || std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    std::string users;
    for (const auto &[t, keys] : perType)
      if (std::find(keys.begin(), keys.end(), key) != keys.end()) users += (users.empty() ? "" : ", ") + t;
    node.child(key).fail("key '" + key + "' does not apply to a " + type + " " + what + " (it applies to: " + users +
                         ")");
  }
}

std::string parseType(const JsonNode &node, const std::vector<std::string> &types, const std::string &fallback,
                      const char *what) {
  if (!node.has("type")) {
    if (fallback.empty()) node.fail(std::string("missing required key 'type' (one of the ") + what + " types)");
    return fallback;
  }
  JsonNode typeNode = node.child("type");
  std::string type = typeNode.asString();
  if (std::find(types.begin(), types.end(), type) == types.end()) {
    std::string list;
    for (const std::string &t : types) list += (list.empty() ? "" : ", ") + t;
    typeNode.fail("unknown " + std::string(what) + " type '" + type + "'" + didYouMean(type, types) + " (expected " +
                  list + ")");
  }
  return type;
}

/// A path named in the scene file, relative to the scene's folder; it must exist.
std::string resolveExistingFile(const JsonNode &node, const fs::path &sceneDirectory, const char *what) {
  fs::path path = sceneDirectory / node.asString();
  if (const InputFileRead read = checkInputFile(path.string()); !read.ok())
    node.fail(inputFileProblem(read, std::string(what) + " '" + path.string() + "'"));
  return path.lexically_normal().string();
}

Material parseMaterial(const JsonNode &node, const std::string &name, const fs::path &sceneDirectory,
                       bool spectralScene) {
  node.expectObject();
  static const std::vector<std::string> kTypes = {"lambertian", "mirror", "dielectric", "glossy"};
  std::string type = parseType(node, kTypes, "lambertian", "material");
  checkTypedKeys(node,
                 {"type", "emission", "two_sided", "bump", "bump_scale", "normal_map", "texture_wrap", "texture_scale"},
                 {{"lambertian", {"reflectance", "diffuse_transmittance", "texture"}},
                  {"mirror", {"reflectance"}},
                  {"dielectric", {"ior", "transmittance", "roughness"}},
                  {"glossy", {"reflectance", "specular", "roughness", "diffuse_transmittance", "texture"}}},
                 type, "material");
  Material m;
  m.name = name;
  m.definedAt = node.location();
  detail::MaterialFieldNames names;
  auto value = [&](const char *key, const Bands &fallback, std::optional<SampledSpectrum> &spectrum) {
    return detail::parseBandValue(node, key, fallback, spectralScene, spectrum);
  };
  // With a texture the reflectance multiplies it, and defaults to 1: the texture is the reflectance.
  const Bands defaultReflectance(node.has("texture") ? 1.0 : 0.5);
  if (type == "lambertian") {
    m.kind = MaterialKind::Lambertian;
    m.diffuse = value("reflectance", defaultReflectance, m.spectra.diffuse);
  } else if (type == "mirror") {
    m.kind = MaterialKind::Mirror;
    m.diffuse = Bands(0.0);
    m.specular = value("reflectance", Bands(1.0), m.spectra.specular);
    names.specular = "reflectance";
  } else if (type == "dielectric") {
    m.kind = MaterialKind::Dielectric;
    m.diffuse = Bands(0.0);
    m.ior = node.number("ior", 1.5);
    m.specular = value("transmittance", Bands(1.0), m.spectra.specular);
    names.specular = "transmittance";
    // GGX α of rough glass; 0, the default, is smooth glass (checkMaterial: 0 or (0, 1]).
    m.transmissionRoughness = node.number("roughness", 0.0);
  } else {
    m.kind = MaterialKind::Glossy;
    m.specular = value("specular", Bands(0.2), m.spectra.specular);
    // With a texture and no reflectance, the most a glossy base may reflect: 1 − specular.
    m.diffuse =
        value("reflectance", node.has("texture") ? Bands(1.0) - m.specular : defaultReflectance, m.spectra.diffuse);
    m.roughness = node.number("roughness", 0.2);
  }
  m.emission = value("emission", Bands(0.0), m.spectra.emission);
  if (m.kind == MaterialKind::Lambertian || m.kind == MaterialKind::Glossy) {
    m.transmittance = value("diffuse_transmittance", Bands(0.0), m.spectra.transmittance);
    // Light goes through to the other side: that side must be part of the solution.
    m.twoSided = m.isTranslucent() || m.spectra.transmittance.has_value();
  }
  if (node.has("two_sided")) {
    const JsonNode sided = node.child("two_sided");
    if (!sided.value().is_boolean()) sided.fail("expected true or false, got " + describeJson(sided.value()));
    if (!sided.value().get<bool>() && m.twoSided)
      sided.fail("a material with a diffuse_transmittance is two-sided: light goes through to the other side");
    m.twoSided = sided.value().get<bool>();
    if (m.twoSided && m.kind == MaterialKind::Dielectric)
      sided.fail(
          "a dielectric is the interface between two media: its faces' sides are inside and outside, "
          "so it cannot be two-sided (a thin glass pane is two faces, one per side)");
  }
  if (node.has("texture")) {
    m.diffuseTexture = resolveExistingFile(node.child("texture"), sceneDirectory, "texture file");
    m.diffuseTextureFrom = node.child("texture").location();
  }
  if (node.has("bump")) {
    m.bumpTexture = resolveExistingFile(node.child("bump"), sceneDirectory, "bump map file");
    m.bumpTextureFrom = node.child("bump").location();
  }
  if (node.has("normal_map")) {
    m.normalTexture = resolveExistingFile(node.child("normal_map"), sceneDirectory, "normal map file");
    m.normalTextureFrom = node.child("normal_map").location();
  }
  if (node.has("bump") && node.has("normal_map"))
    node.child("normal_map").fail("give a bump (height) map or a normal map, not both");
  m.bumpScale = node.number("bump_scale", 1.0);
  if (node.has("texture_wrap")) {
    JsonNode wrap = node.child("texture_wrap");
    std::string value = wrap.asString();
    if (value != "repeat" && value != "clamp") wrap.fail("expected \"repeat\" or \"clamp\", got '" + value + "'");
    m.textureWrap = value == "clamp" ? TextureWrap::Clamp : TextureWrap::Repeat;
  }
  if (node.has("texture_scale")) {
    JsonNode scale = node.child("texture_scale");
    std::vector<JsonNode> pair = scale.value().is_number() ? std::vector<JsonNode>{scale, scale} : scale.asArray(2, 2);
    for (int i = 0; i < 2; ++i) {
      m.uvScale[i] = pair[i].asNumber();
      if (m.uvScale[i] == 0) pair[i].fail("a texture scale of 0 maps the whole surface to one texel");
    }
  }
  detail::checkMaterial(m, node.location(), names);
  detail::checkSpectra(m, node.location(), names);
  return m;
}

/// The object's own transform (scale → rotations in order → translate), in scene units.
Transform parseTransform(const JsonNode &node) {
  node.checkKeys({"scale", "rotate", "translate"});
  Transform result;
  if (node.has("scale")) {
    JsonNode scaleNode = node.child("scale");
    Vec3 s = scaleNode.value().is_number() ? Vec3{1, 1, 1} * scaleNode.asNumber() : scaleNode.asVec3();
    if (s.x == 0 || s.y == 0 || s.z == 0) scaleNode.fail("a scale of 0 flattens the object; expected non-zero factors");
    result = Transform::scale(s);
  }
  if (node.has("rotate")) {
    for (const JsonNode &rotation : node.child("rotate").asArray()) {
      rotation.checkKeys({"axis", "degrees"});
      Vec3 axis = rotation.child("axis").asVec3();
      if (!(length(axis) > 0)) rotation.child("axis").fail("the rotation axis is the zero vector");
      result = Transform::rotate(rotation.child("degrees").asNumber(), axis) * result;
    }
  }
  if (node.has("translate")) result = Transform::translate(node.child("translate").asVec3()) * result;
  return result;
}

struct SceneParser {
  Scene &scene;
  std::string file;
  fs::path directory;
  double metres = 1.0;
  std::map<std::string, std::string> objectPathByName;   // for duplicate names
  size_t jsonMaterialCount = 0;                          // the JSON's materials, which override glTF ones by name
  detail::MaterialNames materialNames{scene.materials};  // findMaterial per object was quadratic in 10⁵ objects

  /// Fails at `node` (the vertex, centre or radius that put them there) when a
  /// vertex added since `first` lies where the ray tracer cannot work
  /// (scene.h): validateScene checks the same, but could name only the file.
  void checkPositions(size_t first, const JsonNode &node) const {
    for (size_t i = first; i < scene.positions.size(); ++i)
      if (!withinCoordinateRange(scene.positions[i]))
        node.fail(
            fmt::format("a vertex at ({:g}, {:g}, {:g}) m, after units and transform, is more than {:g} m "
                        "from the origin; the ray tracer works in single precision",
                        scene.positions[i].x, scene.positions[i].y, scene.positions[i].z, kMaxCoordinateMetres));
  }

  uint32_t materialFor(const JsonNode &object) {
    if (!object.has("material")) return detail::defaultMaterialIndex(scene);
    JsonNode node = object.child("material");
    std::string name = node.asString();
    int index = materialNames.find(name);
    if (index < 0) {
      std::vector<std::string> known;
      for (const Material &m : scene.materials) known.push_back(m.name);
      node.fail("material '" + name + "' is not defined in /materials" + didYouMean(name, known));
    }
    return static_cast<uint32_t>(index);
  }

  void parseObject(const JsonNode &node, size_t index) {
    node.expectObject();
    static const std::vector<std::string> kTypes = {"quad", "triangle", "obj", "gltf", "mgf", "sphere"};
    std::string type = parseType(node, kTypes, "", "object");
    checkTypedKeys(node, {"name", "type", "material", "transform"},
                   {{"quad", {"vertices", "uv"}},
                    {"triangle", {"vertices", "uv"}},
                    {"obj", {"file"}},
                    {"gltf", {"file"}},
                    {"mgf", {"file"}},
                    {"sphere", {"center", "radius", "segments"}}},
                   type, "object");
    std::string name = node.string("name", type + "-" + std::to_string(index));
    if (name.empty()) node.child("name").fail("an object name cannot be empty");
    auto [previous, inserted] = objectPathByName.emplace(name, node.path());
    if (!inserted) node.fail("object name '" + name + "' is already used by " + previous->second);

    Transform local = node.has("transform") ? parseTransform(node.child("transform")) : Transform{};
    Transform toWorld = Transform::scale(Vec3{metres, metres, metres}) * local;
    const bool flip = toWorld.determinant() < 0;

    if (type == "obj") {
      std::string objPath = (directory / node.child("file").asString()).string();
      int material = -1;
      std::string materialName;
      if (node.has("material")) {
        materialName = node.child("material").asString();
        material = materialNames.find(materialName);
      }
      InputLocation fileLocation = node.child("file").location();
      InputLocation materialLocation = node.has("material") ? node.child("material").location() : fileLocation;
      size_t objectsBefore = scene.objects.size();
      detail::appendObjFromScene(scene, objPath, toWorld, name, material, materialName, fileLocation, materialLocation);
      if (scene.objects.size() == objectsBefore)
        scene.warnings.push_back("object '" + name + "' (" + objPath + ") has no faces");
      return;
    }

    if (type == "gltf") {
      // Its cameras are not read: the scene's camera (or the framing one) is the view.
      std::string gltfPath = (directory / node.child("file").asString()).string();
      const int material = node.has("material") ? static_cast<int>(materialFor(node)) : -1;
      size_t objectsBefore = scene.objects.size();
      detail::appendGltf(scene, gltfPath, toWorld, name, material, jsonMaterialCount, node.child("file").location());
      if (scene.objects.size() == objectsBefore)
        scene.warnings.push_back("object '" + name + "' (" + gltfPath + ") has no meshes in its scene");
      return;
    }

    if (type == "mgf") {
      // MGF files carry their own materials (docs/scene-format.md#mgf-scenes).
      if (node.has("material"))
        node.child("material").fail("an mgf object takes its materials from the MGF file; remove 'material'");
      std::string mgfPath = (directory / node.child("file").asString()).string();
      size_t objectsBefore = scene.objects.size();
      detail::appendMgf(scene, mgfPath, toWorld, name, node.child("file").location());
      if (scene.objects.size() == objectsBefore)
        scene.warnings.push_back("object '" + name + "' (" + mgfPath + ") has no faces");
      return;
    }

    uint32_t material = materialFor(node);
    uint32_t object = static_cast<uint32_t>(scene.objects.size());
    scene.objects.push_back(SceneObject{name, file + " " + node.path()});
    if (type == "sphere") {
      Vec3 center = node.child("center").asVec3();
      JsonNode radiusNode = node.child("radius");
      double radius = radiusNode.asNumber();
      if (!(radius > 0)) radiusNode.fail("sphere radius " + radiusNode.value().dump() + " must be > 0");
      int segments = static_cast<int>(node.integer("segments", 48, 4, 1024));
      const size_t first = scene.positions.size();
      detail::addUvSphere(scene, center, radius, segments, toWorld, material, object);
      checkPositions(first, withinCoordinateRange(toWorld.point(center)) ? radiusNode : node.child("center"));
      return;
    }
    const size_t count = type == "quad" ? 4 : 3;
    std::vector<uint32_t> vertices;
    for (const JsonNode &vertex : node.child("vertices").asArray(count, count)) {
      vertices.push_back(static_cast<uint32_t>(scene.positions.size()));
      scene.positions.push_back(toWorld.point(vertex.asVec3()));
      checkPositions(vertices.back(), vertex);
    }
    // Texture coordinates: given, or the unit square (triangle) in vertex order.
    static constexpr double kDefaultUv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    std::vector<int32_t> uvs;
    std::vector<JsonNode> given;
    if (node.has("uv")) given = node.child("uv").asArray(count, count);
    for (size_t k = 0; k < count; ++k) {
      uvs.push_back(static_cast<int32_t>(scene.uvs.size() / 2));
      const double *fallback = kDefaultUv[count == 3 && k == 2 ? 3 : k];
      std::vector<JsonNode> uv = given.empty() ? std::vector<JsonNode>{} : given[k].asArray(2, 2);
      scene.uvs.push_back(uv.empty() ? fallback[0] : uv[0].asNumber());
      scene.uvs.push_back(uv.empty() ? fallback[1] : uv[1].asNumber());
    }
    detail::addPolygon(scene, vertices, uvs, {}, material, object, flip);
  }

  /// "grids": calculation grids (docs/scene-format.md), in scene units.
  void parseGrids(const JsonNode &grids) {
    std::vector<JsonNode> entries = grids.asArray();
    for (size_t index = 0; index < entries.size(); ++index) {
      const JsonNode &node = entries[index];
      node.expectObject();
      node.checkKeys({"name", "origin", "u", "v", "nu", "nv", "normal"});
      CalculationGrid grid;
      grid.name = node.string("name", "grid-" + std::to_string(index));
      if (grid.name.empty()) node.child("name").fail("a grid name cannot be empty");
      for (const CalculationGrid &other : scene.grids)
        if (other.name == grid.name) node.child("name").fail("a second grid named '" + grid.name + "'");
      grid.origin = node.child("origin").asVec3() * metres;
      grid.u = node.child("u").asVec3() * metres;
      grid.v = node.child("v").asVec3() * metres;
      grid.nu = static_cast<int>(node.integer("nu", 1, 1, kMaxGridPoints));
      grid.nv = static_cast<int>(node.integer("nv", 1, 1, kMaxGridPoints));
      if (grid.pointCount() > size_t(kMaxGridPoints))
        node.child("nv").fail(
            fmt::format("a grid of {} × {} points is more than the {} allowed", grid.nu, grid.nv, kMaxGridPoints));
      const double extent = std::max(length(grid.u), length(grid.v));
      if (!(length(cross(grid.u, grid.v)) > 1e-12 * extent * extent))
        node.child("v").fail("u and v span no area (zero or parallel)");
      for (const Vec3 &corner :
           {grid.origin, grid.origin + grid.u, grid.origin + grid.v, grid.origin + grid.u + grid.v})
        if (!withinCoordinateRange(corner))
          node.child("origin").fail(fmt::format("the grid reaches beyond ±{:g} m", kMaxCoordinateMetres));
      if (node.has("normal")) {
        JsonNode normal = node.child("normal");
        const Vec3 n = normal.asVec3();
        if (!(length(n) > 0)) normal.fail("the normal has zero length");
        grid.normal = normalize(n);
      } else {
        grid.normal = normalize(cross(grid.u, grid.v));
      }
      scene.grids.push_back(grid);
    }
  }

  void parse(const Json &document) {
    JsonNode root(document, file, "");
    root.checkKeys({"version", "units", "camera", "image", "render", "spectral", "materials", "objects", "grids",
                    "lights", "luminaires"});
    if (root.has("version")) {
      JsonNode version = root.child("version");
      if (version.asInteger(INT64_MIN, INT64_MAX) != 1)
        version.fail("unsupported scene format version " + version.value().dump() + "; this Radiant reads version 1");
    }
    if (root.has("units")) metres = parseUnits(root.child("units"));
    scene.metresPerUnit = metres;

    // Image, render settings and camera first: checked before any allocation.
    RenderSettings &render = scene.render;
    if (root.has("image")) {
      JsonNode image = root.child("image");
      image.checkKeys({"width", "height"});
      render.width = static_cast<int>(image.integer("width", render.width, 1, 16384));
      render.height = static_cast<int>(image.integer("height", render.height, 1, 16384));
    }
    if (root.has("render")) {
      JsonNode node = root.child("render");
      node.checkKeys({"spp", "seed", "max_depth", "time", "exposure"});
      render.samplesPerPixel = static_cast<int>(node.integer("spp", render.samplesPerPixel, 1, 1048576));
      render.seed = static_cast<uint64_t>(node.integer("seed", static_cast<int64_t>(render.seed), 0, INT64_MAX));
      render.maxDepth = static_cast<int>(node.integer("max_depth", render.maxDepth, 0, 1 << 20));
      render.timeBudgetSeconds = node.number("time", render.timeBudgetSeconds);
      if (render.timeBudgetSeconds < 0) node.child("time").fail("time budget must be ≥ 0 seconds (0: no budget)");
      render.exposure = node.number("exposure", render.exposure);
    }
    detail::checkRenderSettings(render, InputLocation{file, 0, 0, "/"});
    bool hasCamera = root.has("camera");
    if (hasCamera) {
      JsonNode node = root.child("camera");
      node.checkKeys({"eye", "target", "up", "fov"});
      CameraSettings &camera = scene.camera;
      camera.eye = node.child("eye").asVec3() * metres;
      camera.target = node.child("target").asVec3() * metres;
      camera.up = node.vec3("up", Vec3{0, 1, 0});
      camera.verticalFovDegrees = node.number("fov", 40.0);
      detail::checkCamera(camera, node.location());
    }

    // Spectral when the scene says so or gives any spectrum (docs/spectral.md).
    if (root.has("spectral"))
      scene.spectral = detail::parseSpectralSettings(root.child("spectral"));
    else if (root.has("materials") && detail::materialsGiveSpectra(root.child("materials")))
      scene.spectral = detail::defaultSpectralSettings();
    if (root.has("materials")) {
      JsonNode materials = root.child("materials");
      materials.expectObject();
      for (auto it = materials.value().begin(); it != materials.value().end(); ++it) {
        if (it.key() == "comment") continue;
        JsonNode node = materials.child(it.key());
        if (it.key().empty()) node.fail("a material name cannot be empty");
        scene.materials.push_back(parseMaterial(node, it.key(), directory, scene.spectral.enabled()));
      }
    }
    jsonMaterialCount = scene.materials.size();
    JsonNode objects = root.child("objects");
    std::vector<JsonNode> entries = objects.asArray();
    for (size_t i = 0; i < entries.size(); ++i) parseObject(entries[i], i);

    if (root.has("grids")) parseGrids(root.child("grids"));
    if (root.has("lights")) detail::parseLights(scene, root.child("lights"), metres);
    if (root.has("luminaires")) detail::parseLuminaires(scene, root.child("luminaires"), metres, directory);

    if (!hasCamera) scene.camera = detail::frameBounds(scene);
    if (scene.spectral.enabled()) detail::checkSpectralScene(scene);
  }
};

/// The name of a 3D format Radiant does not read, recognised by the file's
/// extension or its first bytes, or "" (then the file is read as JSON).
std::string unreadFormat(const std::string &extension, const std::string &head) {
  struct Known {
    const char *extension, *name;
  };
  static constexpr Known kKnown[] = {
      {".ply", "PLY"},       {".fbx", "FBX"},  {".dae", "COLLADA"}, {".3ds", "3D Studio"},      {".stl", "STL"},
      {".blend", "Blender"}, {".usd", "USD"},  {".usda", "USD"},    {".usdc", "USD"},           {".usdz", "USD"},
      {".x3d", "X3D"},       {".wrl", "VRML"}, {".pbrt", "pbrt"},   {".xml", "XML (Mitsuba?)"}, {".off", "OFF"},
  };
  for (const Known &k : kKnown)
    if (extension == k.extension) return k.name;
  if (head.rfind("ply\n", 0) == 0 || head.rfind("ply\r\n", 0) == 0) return "PLY";
  if (head.rfind("Kaydara FBX Binary", 0) == 0) return "FBX";
  if (head.rfind("solid ", 0) == 0) return "STL";
  if (head.rfind("BLENDER", 0) == 0) return "Blender";
  return "";
}

/// True for a file that starts like a GLB ("glTF"), whatever its name.
bool startsWithGlbMagic(const std::string &path) {
  return readInputFilePrefix(path, 4) == "glTF";
}

/// A bare .gltf/.glb: its default scene in metres (glTF's unit), viewed from
/// its first perspective camera or, without one, the bare-OBJ framing camera.
Scene loadGltfScene(const std::string &path) {
  Scene scene;
  scene.sourceFile = path;
  const detail::GltfView view = detail::appendGltf(scene, path, Transform{}, fs::path(path).stem().string(), -1, 0,
                                                   InputLocation{path, 0, 0, ""});
  detail::dropRepeatedFaces(scene);
  if (view.hasCamera) {
    scene.camera = view.camera;
    detail::checkCamera(scene.camera, view.cameraFrom);
    if (view.aspectRatio > 0) {
      // The image keeps the default width; the height follows the camera's aspect ratio.
      const double height = std::round(scene.render.width / view.aspectRatio);
      scene.render.height = static_cast<int>(std::clamp(height, 1.0, double(kMaxImageDimension)));
    }
  } else {
    scene.camera = detail::frameBounds(scene);
  }
  detail::loadTextures(scene);
  validateScene(scene);
  return scene;
}

}  // namespace

Scene parseSceneJson(const std::string &text, const std::string &path) {
  Json document = parseJsonText(text, path);
  Scene scene;
  scene.sourceFile = path;
  SceneParser parser{scene, path, fs::path(path).parent_path()};
  parser.parse(document);
  detail::dropRepeatedFaces(scene);
  detail::loadTextures(scene);
  validateScene(scene);
  return scene;
}

Scene loadScene(const std::string &path) {
  Phase phase("loading " + fs::path(path).filename().string());
  const std::string extension = lowercaseExtension(path);
  if (extension == ".obj") {
    Scene scene;
    scene.sourceFile = path;
    // A bare OBJ is taken to be in metres.
    appendObj(scene, path, Transform{}, fs::path(path).stem().string(), -1);
    detail::dropRepeatedFaces(scene);
    scene.camera = detail::frameBounds(scene);
    detail::loadTextures(scene);
    validateScene(scene);
    return scene;
  }
  if (extension == ".gltf" || extension == ".glb" || startsWithGlbMagic(path)) return loadGltfScene(path);
  if (extension == ".mgf") {
    // MGF is in metres by convention; viewed like a bare OBJ.
    Scene scene;
    scene.sourceFile = path;
    detail::appendMgf(scene, path, Transform{}, fs::path(path).stem().string(), InputLocation{path, 0, 0, ""});
    detail::dropRepeatedFaces(scene);
    scene.camera = detail::frameBounds(scene);
    validateScene(scene);
    return scene;
  }
  const std::string text = readInputFile(path, InputLocation{path, 0, 0, ""}, "scene file");
  const std::string head = text.substr(0, 32);
  if (head.rfind("RADIANT-SOLUTION", 0) == 0)
    throw InputError(InputLocation{path, 0, 0, ""},
                     "this is a Radiant solution file (from radiant solve -o), not a scene: give the scene, and "
                     "the solution with --solution");
  const std::string format = unreadFormat(extension, head);
  if (!format.empty())
    throw InputError(
        InputLocation{path, 0, 0, ""},
        "this is a " + format +
            " file, which Radiant does not read: a scene is a JSON scene file "
            "(docs/scene-format.md), a Wavefront OBJ model (.obj), a glTF 2.0 file (.gltf, .glb) or an MGF "
            "file (.mgf)");
  try {
    return parseSceneJson(text, path);
  } catch (const InputError &e) {
    // A file that is not JSON at all, under a name that does not say JSON: say
    // what Radiant expected rather than only where the JSON broke.
    if (extension == ".json" || e.message().rfind("invalid JSON", 0) != 0 || e.location().line > 1) throw;
    throw InputError(e.location(), e.message() + " (Radiant reads JSON scene files and .obj models; '" + path +
                                       "' is read as JSON because its name does not end in .obj, .gltf, .glb or .mgf)");
  }
}

}  // namespace radiant
