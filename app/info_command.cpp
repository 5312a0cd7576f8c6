// radiant info SCENE — what Radiant made of a scene file, for a person (or,
// with --json, for a script), before any render or solve: its bounds in
// scene units and metres with the units assumed and where they came from,
// what it holds (faces, objects, materials, emitters, lights, textures,
// grids), what the loader dropped or merged and why, and which solver a
// solve with these flags would run (docs/cli.md, `radiant info`).
//
// The scene is loaded by the loader `render` and `solve` use (loadScene), so
// what it prints is what they would work on. A scene with no faces is
// described, not refused: info reports, it does not judge (exit status 0).
#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "cluster/cluster.h"
#include "commands.h"
#include "phase_console.h"
#include "radiosity_options.h"
#include "scene/json_reader.h"
#include "scene/load_scene.h"
#include "util/file_extension.h"

namespace radiant {

namespace {

struct InfoCommandOptions {
  std::string scenePath;
  RadiosityCommandOptions radiosity;
  bool json = false;
  bool quiet = false;
};

/// An axis-aligned box, in metres; empty until a point is added.
struct Bounds {
  Vec3 lo, hi;
  bool empty = true;
  void add(const Vec3 &p) {
    if (empty) {
      lo = hi = p;
      empty = false;
      return;
    }
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  }
  Vec3 size() const { return hi - lo; }
  double largestExtent() const { return std::max({size().x, size().y, size().z}); }
};

/// The units a scene's lengths were read in, and who said so.
struct UnitsInfo {
  std::string format;  ///< "JSON scene", "OBJ model", "glTF file", "MGF file"
  std::string name;    ///< as given ("millimetres", "mm") or the format's own ("metres")
  std::string source;  ///< where the units came from, for a person
  bool jsonScene = false;
};

/// The same dispatch as loadScene (scene/load_scene.cpp), which does not
/// record it: the format by extension (or a GLB's magic bytes), and for a
/// JSON scene its "units" key, read again from the file the loader has just
/// accepted.
UnitsInfo unitsOf(const std::string &path) {
  const std::string extension = lowercaseExtension(path);
  char head[4] = {};
  std::ifstream magic(path, std::ios::binary);
  const bool glb = magic.read(head, 4) && std::string(head, 4) == "glTF";
  if (extension == ".obj") return {"OBJ model", "metres", "as a bare OBJ is always read", false};
  if (extension == ".gltf" || extension == ".glb" || glb) return {"glTF file", "metres", "glTF's own unit", false};
  if (extension == ".mgf") return {"MGF file", "metres", "MGF's own unit", false};
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  const Json document = parseJsonText(text.str(), path);
  if (document.is_object() && document.contains("units") && document["units"].is_string())
    return {"JSON scene", document["units"].get<std::string>(), "given by the scene file's \"units\"", true};
  return {"JSON scene", "metres", "the default, as the scene file gives no \"units\"", true};
}

/// A plain-language warning when the scene's size is implausible for its
/// units (a model in millimetres read as metres is a kilometre-sized room),
/// or "". The thresholds are wide: a building site may span a few hundred
/// metres, the smallest thing worth lighting a few millimetres.
std::string sizeWarning(const Bounds &bounds, const Scene &scene, const UnitsInfo &units) {
  if (bounds.empty) return "";
  const double extent = bounds.largestExtent();
  constexpr double kLargestPlausibleMetres = 1000, kSmallestPlausibleMetres = 1e-3;
  const bool tooLarge = extent > kLargestPlausibleMetres, tooSmall = extent < kSmallestPlausibleMetres;
  if (!tooLarge && !tooSmall) return "";
  // The unit the model was more likely drawn in: millimetres (the CAD
  // default) for a model far too large, metres for one far too small.
  const char *likely = tooLarge ? "millimetres" : "metres";
  const char *key = tooLarge ? "mm" : "m";
  const bool likelyIsCurrent = tooLarge ? scene.metresPerUnit <= 1e-3 : scene.metresPerUnit >= 1;
  std::string text = fmt::format("the scene is {:.4g} m across, which looks {} for {} ({})", extent,
                                 tooLarge ? "too large" : "too small", units.name, units.source);
  if (likelyIsCurrent)
    return text + ": check the model's scale (a JSON object's \"transform\": {\"scale\": …}, docs/scene-format.md)";
  text += fmt::format(": is this model in {}? give \"units\": \"{}\"", likely, key);
  if (units.jsonScene) return text + " at the top of the scene file (docs/scene-format.md, Units)";
  const char *objectType = units.format == "OBJ model" ? "obj" : units.format == "glTF file" ? "gltf" : "mgf";
  text += fmt::format(" in a JSON scene that names this file in an object of type \"{}\"", objectType);
  return text + " (docs/scene-format.md, Units)";
}

/// The symbol the scene's lengths are shown with ("mm"), from its metres per unit.
std::string unitLabel(double metresPerUnit) {
  struct Label {
    double metres;
    const char *label;
  };
  for (const Label &l : {Label{1, "m"}, Label{0.01, "cm"}, Label{1e-3, "mm"}, Label{0.0254, "in"}, Label{0.3048, "ft"}})
    if (metresPerUnit == l.metres) return l.label;
  return fmt::format("units of {:g} m", metresPerUnit);
}

std::string formatPoint(const Vec3 &p) {
  return fmt::format("({:.6g}, {:.6g}, {:.6g})", p.x, p.y, p.z);
}
std::string formatSize(const Vec3 &s) {
  return fmt::format("{:.6g} × {:.6g} × {:.6g}", s.x, s.y, s.z);
}

Json jsonVec(const Vec3 &v) {
  return Json::array({v.x, v.y, v.z});
}

/// Bounds as JSON: min, max and size in scene units and in metres; null when empty.
Json jsonBounds(const Bounds &b, double metresPerUnit) {
  if (b.empty) return nullptr;
  Json j;
  j["min"] = jsonVec(b.lo / metresPerUnit);
  j["max"] = jsonVec(b.hi / metresPerUnit);
  j["size"] = jsonVec(b.size() / metresPerUnit);
  j["min_metres"] = jsonVec(b.lo);
  j["max_metres"] = jsonVec(b.hi);
  j["size_metres"] = jsonVec(b.size());
  return j;
}

const char *lightKindName(PointLightKind kind) {
  switch (kind) {
    case PointLightKind::Point:
      return "point";
    case PointLightKind::Spot:
      return "spot";
    case PointLightKind::Photometric:
      return "photometric";
  }
  return "?";
}

std::string plural(size_t n, const char *one, const char *many) {
  return fmt::format("{} {}", n, n == 1 ? one : many);
}

/// The most objects listed one by one in the text output (--json lists all).
constexpr size_t kListedObjects = 20;

std::string objectNameOf(const Scene &scene, uint32_t object) {
  return object < scene.objects.size() ? scene.objects[object].name : fmt::format("#{}", object);
}

/// What the loaders dropped and merged (scene/load_changes.h), kind by kind:
/// the count, and the first few by object and position in scene units.
Json jsonLoadChanges(const Scene &scene, double metresPerUnit) {
  Json j;
  for (size_t k = 0; k < kLoadChangeKinds; ++k) {
    const auto kind = LoadChangeKind(k);
    Json listed = Json::array();
    for (const LoadChange &c : scene.loadChanges.listed)
      if (c.kind == kind)
        listed.push_back({{"object", objectNameOf(scene, c.object)},
                          {"position", isFinite(c.position) ? jsonVec(c.position / metresPerUnit) : Json(nullptr)},
                          {"position_metres", isFinite(c.position) ? jsonVec(c.position) : Json(nullptr)},
                          {"reason", c.reason}});
    j[loadChangeKey(kind)] = {{"what", loadChangeName(kind)},
                              {"action", loadChangeAction(kind)},
                              {"count", scene.loadChanges.count(kind)},
                              {"listed", listed}};
  }
  // No loader welds vertices (faces keep the indices they were given), so
  // there is nothing to list; said so that a script need not guess.
  j["welded_vertices"] = {{"what", "welded vertices"}, {"action", "merged"}, {"count", 0}, {"listed", Json::array()}};
  return j;
}

/// A kind's count for a person: "2 degenerate faces".
std::string describeCount(LoadChangeKind kind, size_t n) {
  switch (kind) {
    case LoadChangeKind::DegenerateFace:
      return plural(n, "degenerate face", "degenerate faces");
    case LoadChangeKind::RepeatedFace:
      return plural(n, "repeated face", "repeated faces");
    case LoadChangeKind::CollinearQuad:
      return plural(n, "quad with three corners on a line, kept as a triangle",
                    "quads with three corners on a line, kept as triangles");
    case LoadChangeKind::BackToBack:
      return plural(n, "pair of faces back to back, made one two-sided surface",
                    "pairs of faces back to back, each made one two-sided surface");
  }
  return "?";
}

/// The "dropped:" and "merged:" rows, each change listed below by object and position.
void printLoadChanges(const Scene &scene, double metresPerUnit, const std::string &label) {
  for (const std::string action : {"dropped", "merged"}) {
    std::string summary;
    for (size_t k = 0; k < kLoadChangeKinds; ++k) {
      const auto kind = LoadChangeKind(k);
      if (loadChangeAction(kind) == action && scene.loadChanges.count(kind) > 0)
        summary += (summary.empty() ? "" : ", ") + describeCount(kind, scene.loadChanges.count(kind));
    }
    if (summary.empty())
      summary = action == "dropped" ? "no degenerate or repeated faces" : "nothing (no vertices are welded either)";
    fmt::print("{:<11}{}\n", action + ":", summary);
    for (size_t k = 0; k < kLoadChangeKinds; ++k) {
      const auto kind = LoadChangeKind(k);
      if (loadChangeAction(kind) != action) continue;
      for (const LoadChange &c : scene.loadChanges.listed)
        if (c.kind == kind)
          fmt::print("  {} in '{}' at {}: {}\n", loadChangeName(kind), objectNameOf(scene, c.object),
                     isFinite(c.position) ? formatPoint(c.position / metresPerUnit) + " " + label
                                          : std::string("no finite corner"),
                     c.reason);
      const size_t count = scene.loadChanges.count(kind);
      if (count > LoadChanges::kListedPerKind)
        fmt::print("  … and {} more ({} in all; the first {} of each kind are listed)\n",
                   count - LoadChanges::kListedPerKind, describeCount(kind, count), LoadChanges::kListedPerKind);
    }
  }
}

}  // namespace

CommandRunner addInfoCommand(CLI::App &app) {
  auto o = std::make_shared<InfoCommandOptions>();
  app.add_option("scene", o->scenePath,
                 "Scene file: JSON (docs/scene-format.md), a bare .obj model, a glTF 2.0 file (.gltf, .glb) or an "
                 "MGF file (.mgf)")
      ->required();
  app.add_flag("--json", o->json, "Print the same as one JSON object, for scripts");
  app.add_flag("-q,--quiet", o->quiet, "No loading progress on stderr");
  addRadiosityOptions(app, o->radiosity);

  return [o]() {
    checkRadiosityOptions(o->radiosity, true, "");
    Scene scene;
    {
      const ConsolePhases phases(!o->quiet && cluster::isRoot());
      scene = loadScene(o->scenePath);
    }
    if (!cluster::isRoot()) return 0;
    const UnitsInfo units = unitsOf(o->scenePath);
    const double unit = scene.metresPerUnit;
    const std::string label = unitLabel(unit);

    // Front faces are the input's polygons; back faces are the second sides
    // Scene::addBackFaces gave two-sided materials, and not counted as input.
    size_t frontFaces = 0, backFaces = 0, emittingFaces = 0, frontTriangles = 0;
    Bounds bounds;
    std::vector<size_t> objectFaces(scene.objects.size(), 0);
    std::vector<Bounds> objectBounds(scene.objects.size());
    for (const Face &f : scene.faces) {
      // As chooseSolver counts them: a face of an emitting material, either side.
      emittingFaces += scene.materials[f.material].isEmitter();
      if (f.back) {
        ++backFaces;
        continue;
      }
      ++frontFaces;
      for (int k = 0; k < f.vertexCount; ++k) bounds.add(scene.positions[f.vertices[k]]);
      if (f.object < scene.objects.size()) {
        ++objectFaces[f.object];
        for (int k = 0; k < f.vertexCount; ++k) objectBounds[f.object].add(scene.positions[f.vertices[k]]);
      }
    }
    for (const Triangle &t : scene.triangles) frontTriangles += !scene.faces[t.face].back;
    std::vector<std::string> emittingMaterials;
    for (const Material &m : scene.materials)
      if (m.isEmitter()) emittingMaterials.push_back(m.name);
    const std::string sizeNote = sizeWarning(bounds, scene, units);
    const bool nothingToSolve = frontFaces == 0;
    SolverChoice choice;
    bool importanceRefused = false;
    if (!nothingToSolve) {
      MeshOptions meshOptions;
      const SolverOptions solverOptions = solverOptionsFor(scene, o->radiosity, meshOptions);
      choice = chooseSolver(scene, solverOptions);
      // solve refuses --importance unless it runs hierarchical (radiosity_options.cpp solveScene).
      importanceRefused = solverOptions.importance && choice.solver != "hierarchical";
    }

    if (o->json) {
      Json j;
      j["file"] = o->scenePath;
      j["format"] = units.format;
      j["units"] = {{"name", units.name}, {"metres_per_unit", unit}, {"source", units.source}};
      j["bounds"] = jsonBounds(bounds, unit);
      j["size_warning"] = sizeNote.empty() ? Json(nullptr) : Json(sizeNote);
      j["faces"] = frontFaces;
      j["back_faces"] = backFaces;
      j["triangles"] = frontTriangles;
      j["emitting_faces"] = emittingFaces;
      j["materials"] = scene.materials.size();
      j["emitting_materials"] = emittingMaterials;
      j["textures"] = scene.textures.size();
      j["shading_normals"] = !scene.normals.empty();
      Json spectral = {{"enabled", scene.spectral.enabled()}};
      if (scene.spectral.enabled()) {
        spectral["wavelengths_nm"] = scene.spectral.wavelengths;
        spectral["passes"] = scene.spectral.passCount();
      }
      j["spectral"] = spectral;
      Json objects = Json::array();
      for (size_t i = 0; i < scene.objects.size(); ++i)
        objects.push_back({{"name", scene.objects[i].name},
                           {"faces", objectFaces[i]},
                           {"bounds", jsonBounds(objectBounds[i], unit)}});
      j["objects"] = objects;
      Json lights = Json::array();
      for (const PointLight &light : scene.lights)
        lights.push_back({{"name", light.name},
                          {"kind", lightKindName(light.kind)},
                          {"position_metres", jsonVec(light.position)},
                          {"description", describeLight(light)}});
      j["lights"] = lights;
      Json grids = Json::array();
      for (const CalculationGrid &g : scene.grids)
        grids.push_back({{"name", g.name}, {"points", g.pointCount()}, {"nu", g.nu}, {"nv", g.nv}});
      j["grids"] = grids;
      j["dropped_degenerate_faces"] = scene.droppedDegenerateFaces;
      j["load_changes"] = jsonLoadChanges(scene, unit);
      j["warnings"] = scene.warnings;
      j["nothing_to_solve"] = nothingToSolve;
      j["solver"] = nothingToSolve ? Json(nullptr)
                                   : Json{{"name", choice.solver},
                                          {"reason", choice.reason},
                                          {"requested", o->radiosity.solver},
                                          {"importance_refused", importanceRefused}};
      fmt::print("{}\n", j.dump(2));
      return 0;
    }

    constexpr const char *kRow = "{:<11}{}\n";
    fmt::print(kRow, "scene:", fmt::format("{} ({})", o->scenePath, units.format));
    fmt::print(kRow, "units:", fmt::format("{} (1 unit = {:g} m), {}", units.name, unit, units.source));
    if (bounds.empty) {
      fmt::print(kRow, "bounds:", "none (no faces)");
    } else {
      fmt::print(kRow, "bounds:",
                 fmt::format("min {}, max {} {}", formatPoint(bounds.lo / unit), formatPoint(bounds.hi / unit), label));
      if (unit != 1)
        fmt::print(kRow, "", fmt::format("min {}, max {} m", formatPoint(bounds.lo), formatPoint(bounds.hi)));
      fmt::print(kRow, "size:", fmt::format("{} {}", formatSize(bounds.size() / unit), label));
      if (unit != 1) fmt::print(kRow, "", fmt::format("{} m", formatSize(bounds.size())));
    }
    std::string faces = plural(frontFaces, "input face", "input faces");
    faces += fmt::format(", {}", plural(frontTriangles, "triangle", "triangles"));
    if (backFaces > 0)
      faces += fmt::format(" (and {} for two-sided materials)", plural(backFaces, "back face", "back faces"));
    fmt::print(kRow, "faces:", faces);
    fmt::print(kRow, "objects:", scene.objects.size());
    const size_t listed = std::min(scene.objects.size(), kListedObjects);
    size_t nameWidth = 0;
    for (size_t i = 0; i < listed; ++i) nameWidth = std::max(nameWidth, scene.objects[i].name.size());
    nameWidth = std::min<size_t>(nameWidth, 32);
    for (size_t i = 0; i < listed; ++i) {
      const std::string faceCount = plural(objectFaces[i], "face", "faces");
      if (objectBounds[i].empty)
        fmt::print("  {:<{}}  no faces\n", scene.objects[i].name, nameWidth);
      else
        fmt::print("  {:<{}}  {:>11}, min {}, max {} {}\n", scene.objects[i].name, nameWidth, faceCount,
                   formatPoint(objectBounds[i].lo / unit), formatPoint(objectBounds[i].hi / unit), label);
    }
    if (scene.objects.size() > kListedObjects)
      fmt::print("  … and {} more (--json lists them all)\n", scene.objects.size() - kListedObjects);
    std::string materials = fmt::format("{}", scene.materials.size());
    if (!emittingMaterials.empty()) {
      std::string names;
      for (const std::string &name : emittingMaterials) names += (names.empty() ? "" : ", ") + name;
      materials += fmt::format(" ({} emitting: {})", emittingMaterials.size(), names);
    }
    fmt::print(kRow, "materials:", materials);
    fmt::print(kRow, "emitters:",
               fmt::format("{}, {}", plural(emittingFaces, "emitting face", "emitting faces"),
                           plural(scene.lights.size(), "light", "lights")));
    for (const PointLight &light : scene.lights)
      fmt::print("  {}; {}, at {} {}\n", describeLight(light), lightKindName(light.kind),
                 formatPoint(light.position / unit), label);
    fmt::print(kRow, "textures:", scene.textures.size());
    fmt::print(kRow, "grids:", scene.grids.size());
    for (const CalculationGrid &g : scene.grids)
      fmt::print("  {}: {} × {} = {}\n", g.name, g.nu, g.nv, plural(g.pointCount(), "point", "points"));
    fmt::print(kRow, "normals:",
               scene.normals.empty() ? "no shading normals (flat faces)" : "shading normals present (smooth shading)");
    if (scene.spectral.enabled())
      fmt::print(kRow, "spectral:",
                 fmt::format("yes, {} wavelengths from {:g} to {:g} nm ({})", scene.spectral.wavelengths.size(),
                             scene.spectral.wavelengths.front(), scene.spectral.wavelengths.back(),
                             plural(size_t(scene.spectral.passCount()), "pass", "passes")));
    else
      fmt::print(kRow, "spectral:", "no (RGB)");
    printLoadChanges(scene, unit, label);
    if (scene.warnings.empty() && sizeNote.empty()) fmt::print(kRow, "warnings:", "none");
    if (!sizeNote.empty()) fmt::print("warning: {}\n", sizeNote);
    for (const std::string &warning : scene.warnings) fmt::print("warning: {}\n", warning);
    if (nothingToSolve) {
      fmt::print(kRow, "solver:", "nothing to solve: the scene has no faces");
    } else {
      fmt::print(kRow, "solver:",
                 fmt::format("{}{}: {}", choice.solver, o->radiosity.solver == "auto" ? " (auto)" : "", choice.reason));
      if (importanceRefused)
        fmt::print("  solve would refuse --importance: it applies only to the hierarchical solver\n");
    }
    return 0;
  };
}

}  // namespace radiant
