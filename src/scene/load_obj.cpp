// Wavefront OBJ/MTL loading through tinyobjloader.
//
// tinyobjloader reads the geometry and the MTL statements, but it accepts some
// malformed lines silently ("v 1 x 2" reads x as 0) and reports out-of-range
// indices with the line of the end of the file. So the OBJ text is scanned once
// here first, line by line, and every malformed statement becomes an InputError
// naming the OBJ file and line. The scan also records each face's usemtl name,
// because a name that only the JSON scene defines is unknown to tinyobjloader.
//
// MTL → Material (docs/scene-format.md has the table):
//   Kd → diffuse ρ, Ke → emission (W·sr⁻¹·m⁻²), map_Kd → diffuseTexture,
//   bump/map_Bump → bumpTexture with -bm → bumpScale;
//   illum 3 with Ks > 0          → Mirror, specular = Ks;
//   illum 4, 6 or 7 with Ni ≠ 1  → Dielectric, ior = Ni, specular = Tf (1 if absent);
//   illum 2 with Ks > 0          → Glossy, specular = Ks, GGX α = sqrt(2 / (Ns + 2))
//                                   (Walter et al. 2007, "Microfacet models for
//                                   refraction through rough surfaces", §5.2:
//                                   the Blinn–Phong exponent with the same
//                                   lobe width as a Beckmann/GGX α);
//   anything else                → Lambertian Kd.

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>

#include "scene/json_reader.h"
#include "scene/load_detail.h"
#include "scene/load_scene.h"
#include "util/input_file.h"
#include "util/parse_number.h"

namespace radiant {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fileError(const std::string &file, int line, const std::string &message) {
  throw InputError(InputLocation{file, line, 0, ""}, message);
}

std::vector<std::string> splitWords(const std::string &line) {
  std::vector<std::string> words;
  std::istringstream in(line);
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

std::vector<std::string> splitLines(const std::string &text) {
  std::vector<std::string> lines;
  std::string line;
  std::istringstream in(text);
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

/// Bounds that keep a malformed file from running the mesher out of time or
/// memory: a face is fan-split into (n − 2) slivers, so an n-gon of 10⁶
/// vertices (seen in a corrupted file) would become a million triangles meeting
/// at one point. Real exporters write n-gons of tens to hundreds of vertices.
constexpr size_t kMaxFaceVertices = 4096;
constexpr long kMaxObjIndex = 1L << 31;

bool parseIndex(const std::string &text, long &value) {
  int64_t parsed = 0;
  if (!parseInteger(text, parsed) || parsed == 0 || parsed < -kMaxObjIndex || parsed > kMaxObjIndex) return false;
  value = static_cast<long>(parsed);
  return true;
}

constexpr const char *kReferenceKinds[3] = {"vertex", "texture coordinate", "normal"};

/// What the pre-scan learns about an OBJ file.
struct ObjScan {
  std::vector<std::string> faceMaterialName;  ///< usemtl in effect per face, in file order
  std::vector<std::string> mtlFiles;          ///< resolved paths of the mtllib files
  std::vector<int> vertexLines;               ///< the line of each 'v', for the coordinate check
};

/// Checks every v/vt/vn/f/usemtl/mtllib line; throws with the OBJ line on the first bad one.
ObjScan scanObj(const std::string &objPath, const std::string &text) {
  ObjScan scan;
  const fs::path directory = fs::path(objPath).parent_path();
  long counts[3] = {0, 0, 0};  // v, vt, vn defined so far
  struct PendingCheck {
    int line;
    long index[3];
  };
  std::vector<PendingCheck> forwardReferences;  // positive indices, checked against the final counts
  std::string currentMaterial;
  std::vector<std::string> lines = splitLines(text);
  for (size_t lineIndex = 0; lineIndex < lines.size(); ++lineIndex) {
    const int line = static_cast<int>(lineIndex) + 1;
    std::vector<std::string> words = splitWords(lines[lineIndex]);
    if (words.empty() || words[0][0] == '#') continue;
    const std::string &keyword = words[0];
    if (keyword == "v" || keyword == "vt" || keyword == "vn") {
      size_t numbers = 0;
      for (size_t k = 1; k < words.size() && words[k][0] != '#'; ++k, ++numbers) {
        double value;
        if (!parseDecimal(words[k], value))
          fileError(objPath, line, "'" + keyword + "' expects finite decimal numbers, got '" + words[k] + "'");
      }
      size_t minimum = keyword == "vt" ? 1 : 3;
      if (numbers < minimum)
        fileError(objPath, line,
                  "'" + keyword + "' expects at least " + std::to_string(minimum) + " numbers, got " +
                      std::to_string(numbers));
      ++counts[keyword == "v" ? 0 : (keyword == "vt" ? 1 : 2)];
      if (keyword == "v") scan.vertexLines.push_back(line);
    } else if (keyword == "f") {
      if (words.size() < 4)
        fileError(objPath, line, "a face needs at least 3 vertices, got " + std::to_string(words.size() - 1));
      if (words.size() - 1 > kMaxFaceVertices)
        fileError(objPath, line,
                  "a face of " + std::to_string(words.size() - 1) + " vertices; Radiant reads faces of at most " +
                      std::to_string(kMaxFaceVertices) + " (split it, or triangulate the model in the exporter)");
      for (size_t k = 1; k < words.size(); ++k) {
        // v, v/vt, v//vn or v/vt/vn; indices are 1-based, negative ones count back.
        std::vector<std::string> parts;
        std::string part;
        std::istringstream in(words[k]);
        while (std::getline(in, part, '/')) parts.push_back(part);
        if (words[k].back() == '/') parts.push_back("");
        if (parts.empty() || parts.size() > 3)
          fileError(objPath, line, "'" + words[k] + "' is not a vertex reference (v, v/vt, v//vn or v/vt/vn)");
        PendingCheck pending{line, {0, 0, 0}};
        for (size_t c = 0; c < parts.size(); ++c) {
          if (c > 0 && parts[c].empty()) continue;
          long index;
          if (!parseIndex(parts[c], index))
            fileError(objPath, line, "'" + words[k] + "' is not a vertex reference (expected non-zero integers)");
          if (index < 0 && -index > counts[c])
            fileError(objPath, line,
                      "relative " + std::string(kReferenceKinds[c]) + " index " + std::to_string(index) +
                          " is out of range (" + std::to_string(counts[c]) + " defined so far)");
          if (index > 0) pending.index[c] = index;
        }
        forwardReferences.push_back(pending);
      }
      scan.faceMaterialName.push_back(currentMaterial);
    } else if (keyword == "usemtl") {
      currentMaterial = words.size() > 1 ? words[1] : "";
    } else if (keyword == "mtllib") {
      for (size_t k = 1; k < words.size(); ++k) {
        fs::path mtl = directory / words[k];
        if (std::optional<std::string> problem = inputFileCheck(mtl.string(), "material library"))
          fileError(objPath, line, *problem);
        scan.mtlFiles.push_back(mtl.string());
      }
    }
  }
  for (const PendingCheck &check : forwardReferences)
    for (int c = 0; c < 3; ++c)
      if (check.index[c] > counts[c])
        fileError(objPath, check.line,
                  std::string(kReferenceKinds[c]) + " index " + std::to_string(check.index[c]) +
                      " is out of range (the file has " + std::to_string(counts[c]) + ")");
  return scan;
}

/// Where each MTL material is declared, for messages.
struct MtlSource {
  std::string file;
  int newmtlLine = 0;
  int mapKdLine = 0;
  int bumpLine = 0;
  std::map<std::string, int> lines;  ///< the line of each value statement (Kd, Ks, …) in this material
};

/// Scans every MTL file, whose text it keeps in `texts` (by path) for tinyobjloader.
std::map<std::string, MtlSource> scanMtlFiles(const std::vector<std::string> &mtlFiles,
                                              std::map<std::string, std::string> &texts) {
  std::map<std::string, MtlSource> sources;
  for (const std::string &file : mtlFiles) {
    if (texts.count(file)) continue;
    const std::string &text = texts[file] = readInputFile(file, InputLocation{file, 0, 0, ""}, "material library");
    std::vector<std::string> lines = splitLines(text);
    MtlSource *current = nullptr;
    for (size_t i = 0; i < lines.size(); ++i) {
      const int line = static_cast<int>(i) + 1;
      std::vector<std::string> words = splitWords(lines[i]);
      if (words.empty() || words[0][0] == '#') continue;
      const std::string &keyword = words[0];
      if (keyword == "newmtl") {
        std::string name = words.size() > 1 ? words[1] : "";
        if (sources.count(name)) {
          current = nullptr;  // tinyobjloader keeps the first definition
          continue;
        }
        current = &sources[name];
        *current = MtlSource{file, line, 0, 0};
      } else if (current && keyword == "map_Kd") {
        current->mapKdLine = line;
      } else if (current && (keyword == "bump" || keyword == "map_Bump" || keyword == "map_bump")) {
        current->bumpLine = line;
      } else if (keyword == "Kd" || keyword == "Ks" || keyword == "Ke" || keyword == "Ka" || keyword == "Tf" ||
                 keyword == "Kt" || keyword == "Ni" || keyword == "Ns" || keyword == "d" || keyword == "Tr" ||
                 keyword == "illum") {
        if (current) current->lines[keyword] = line;
        if (words.size() > 1 && (words[1] == "spectral" || words[1] == "xyz")) continue;
        if (words.size() < 2) fileError(file, line, "'" + keyword + "' expects a value");
        for (size_t k = 1; k < words.size() && words[k][0] != '#'; ++k) {
          double value;
          if (!parseDecimal(words[k], value))
            fileError(file, line, "'" + keyword + "' expects finite decimal numbers, got '" + words[k] + "'");
        }
      }
    }
  }
  return sources;
}

/// tinyobjloader stores floats; widen through the shortest decimal that reads
/// back as the same float, so "Kd 0.6" gives the double 0.6, not 0.60000002.
double widen(float value) {
  char buffer[32];
  auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  double result = value;
  if (error == std::errc()) std::from_chars(buffer, end, result);
  return result;
}

Bands toBands(const tinyobj::real_t values[3]) {
  return Bands(widen(values[0]), widen(values[1]), widen(values[2]));
}
Vec3 toVec3(const std::vector<tinyobj::real_t> &values, size_t i) {
  return {widen(values[i]), widen(values[i + 1]), widen(values[i + 2])};
}

/// The texture path from an MTL statement, relative to the MTL file; it must
/// exist. MTL files written on Windows separate folders with '\' (assimp's
/// spider: `map_Kd .\SpiderTex.jpg`): where the name as given is not a file,
/// it is read with '/' instead.
std::string resolveTexture(const std::string &name, const MtlSource &source, int line, const char *statement) {
  fs::path path = fs::path(source.file).parent_path() / name;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec) && name.find('\\') != std::string::npos) {
    std::string forward = name;
    std::replace(forward.begin(), forward.end(), '\\', '/');
    if (const fs::path alternative = fs::path(source.file).parent_path() / forward;
        fs::is_regular_file(alternative, ec))
      path = alternative;
  }
  if (const InputFileRead file = checkInputFile(path.string()); !file.ok())
    fileError(source.file, line > 0 ? line : source.newmtlLine,
              inputFileProblem(file, "texture '" + path.string() + "' named by " + statement));
  return path.lexically_normal().string();
}

std::string bandsText(const Bands &b) {
  return b[0] == b[1] && b[1] == b[2] ? fmt::format("{:.4g}", b[0])
                                      : fmt::format("{:.4g} {:.4g} {:.4g}", b[0], b[1], b[2]);
}

/// Exporters write MTL values no physical surface has: Kd 1 1 1 ("white")
/// without a texture, Kd + Ks above 1 (3ds Max: Kd 0.2, Ks 0.9), Ks or Tf
/// above 1. Refusing them would leave the model unrenderable, so the values a
/// surface scatters are scaled by one factor, keeping their colour and their
/// ratio, until it scatters no more than it receives (and its diffuse part
/// stays below kMaxDiffuseReflectance); one warning per material says so.
void conserveEnergy(Material &out, const MtlSource &source, std::vector<std::string> &warnings) {
  const bool textured = !out.diffuseTexture.empty();  // Kd multiplies the texture, clamped per texel
  double scale = 1;
  std::string what;
  for (int b = 0; b < kBandCount; ++b) {
    if (out.kind == MaterialKind::Glossy && out.diffuse[b] + out.specular[b] > 1.0) {
      scale = std::min(scale, 1.0 / (out.diffuse[b] + out.specular[b]));
      what = "Kd + Ks = " + bandsText(out.diffuse + out.specular);
    }
    if (out.kind != MaterialKind::Lambertian && out.kind != MaterialKind::Glossy && out.specular[b] > 1.0) {
      scale = std::min(scale, 1.0 / out.specular[b]);
      what = std::string(out.kind == MaterialKind::Mirror ? "Ks" : "Tf") + " = " + bandsText(out.specular);
    }
  }
  Bands diffuse = out.diffuse * scale;
  if (!textured && diffuse.max() > kMaxDiffuseReflectance) {
    scale *= kMaxDiffuseReflectance / diffuse.max();
    if (what.empty()) what = "Kd = " + bandsText(out.diffuse);
  }
  if (scale >= 1 || !(scale > 0)) return;  // nothing to do, or a negative value for checkMaterial to refuse
  out.diffuse = out.diffuse * scale;
  out.specular = out.specular * scale;
  warnings.push_back(source.file + ":" + std::to_string(source.newmtlLine) + ": material '" + out.name + "': " + what +
                     " would reflect as much light as arrives or more; scaled by " + fmt::format("{:.4g}", scale) +
                     " to conserve energy (Kd " + bandsText(out.diffuse) +
                     (out.kind == MaterialKind::Lambertian ? "" : ", Ks " + bandsText(out.specular)) + ")");
}

Material convertMtlMaterial(const tinyobj::material_t &m, const MtlSource &source, std::vector<std::string> &warnings) {
  Material out;
  out.name = m.name;
  out.diffuse = toBands(m.diffuse);
  out.emission = toBands(m.emission);
  Bands specular = toBands(m.specular);
  out.definedAt = InputLocation{source.file, source.newmtlLine, 0, ""};
  detail::MaterialFieldNames names{"Kd", "Ks", "Ke", "Ni", "Ns", source.lines};
  // A negative Ks or Tf would otherwise choose the material's kind silently
  // (no positive component: Lambertian, or a clear dielectric).
  for (const char *keyword : {"Ks", "Tf"}) {
    const Bands value = toBands(keyword[0] == 'K' ? m.specular : m.transmittance);
    const auto line = source.lines.find(keyword);
    if (value.min() < 0)
      fileError(source.file, line != source.lines.end() ? line->second : source.newmtlLine,
                std::string(keyword) + " = " + bandsText(value) +
                    " is negative: a surface cannot reflect or transmit "
                    "less than nothing");
  }
  if (m.illum == 3 && specular.max() > 0) {
    out.kind = MaterialKind::Mirror;
    out.specular = specular;
    out.diffuse = Bands(0.0);
  } else if ((m.illum == 4 || m.illum == 6 || m.illum == 7) && m.ior != 1.0f) {
    out.kind = MaterialKind::Dielectric;
    out.ior = widen(m.ior);
    Bands transmittance = toBands(m.transmittance);
    out.specular = transmittance.max() > 0 ? transmittance : Bands(1.0);
    out.diffuse = Bands(0.0);
    names.specular = "Tf";
  } else if (m.illum == 2 && specular.max() > 0) {
    out.kind = MaterialKind::Glossy;
    out.specular = specular;
    out.roughness = std::sqrt(2.0 / (widen(m.shininess) + 2.0));
    if (!(out.roughness <= 1.0)) out.roughness = std::numeric_limits<double>::quiet_NaN();  // Ns < 0: rejected below
  } else {
    out.kind = MaterialKind::Lambertian;
  }
  auto lineOf = [&](int line) { return InputLocation{source.file, line > 0 ? line : source.newmtlLine, 0, ""}; };
  // tinyobjloader reads three numbers after -s (u v w): "-s 2 2 file.png" loses the file silently.
  if (source.mapKdLine > 0 && m.diffuse_texname.empty())
    fileError(source.file, source.mapKdLine, "map_Kd names no image file (note: -s takes three numbers, -s u v w)");
  if (source.bumpLine > 0 && m.bump_texname.empty())
    fileError(source.file, source.bumpLine, "bump names no image file (note: -s takes three numbers, -s u v w)");
  if (!m.diffuse_texname.empty()) {
    out.diffuseTexture = resolveTexture(m.diffuse_texname, source, source.mapKdLine, "map_Kd");
    out.diffuseTextureFrom = lineOf(source.mapKdLine);
    // -clamp on and -s u v of map_Kd apply to the material's maps.
    out.textureWrap = m.diffuse_texopt.clamp ? TextureWrap::Clamp : TextureWrap::Repeat;
    out.uvScale[0] = widen(m.diffuse_texopt.scale[0]), out.uvScale[1] = widen(m.diffuse_texopt.scale[1]);
  }
  if (!m.bump_texname.empty()) {
    out.bumpTexture = resolveTexture(m.bump_texname, source, source.bumpLine, "bump");
    out.bumpTextureFrom = lineOf(source.bumpLine);
    out.bumpScale = widen(m.bump_texopt.bump_multiplier);
  }
  conserveEnergy(out, source, warnings);
  detail::checkMaterial(out, out.definedAt, names);
  return out;
}

/// tinyobjloader's MTL reader over the texts scanMtlFiles read: its own
/// (MaterialFileReader) opens each file again by name, with no check of what
/// the name is. A name the scan did not see (tinyobjloader reads a backslash in
/// mtllib names as an escape) is read here, through readInputFile's checks.
class MtlTextReader : public tinyobj::MaterialReader {
 public:
  MtlTextReader(fs::path directory, const std::map<std::string, std::string> &texts)
      : directory_(std::move(directory)), texts_(texts) {}
  bool operator()(const std::string &name, std::vector<tinyobj::material_t> *materials,
                  std::map<std::string, int> *materialMap, std::string *warning, std::string *error) override {
    const std::string path = (directory_ / name).string();
    std::string text;
    if (auto known = texts_.find(path); known != texts_.end()) {
      text = known->second;
    } else {
      InputFileRead read = tryReadInputFile(path);
      if (!read.ok()) {
        *warning += inputFileProblem(read, "material library '" + path + "'") + "\n";
        return false;
      }
      text = std::move(read.bytes);
    }
    std::istringstream in(text);
    tinyobj::LoadMtl(materialMap, materials, &in, warning, error);
    return true;
  }

 private:
  fs::path directory_;
  const std::map<std::string, std::string> &texts_;
};

/// A line number quoted in a tinyobjloader message ("line 12" / "line: 12"), or 0.
int lineInMessage(const std::string &message) {
  std::smatch match;
  static const std::regex pattern("line:? ([0-9]+)");
  return std::regex_search(message, match, pattern) ? std::stoi(match[1]) : 0;
}

}  // namespace

void detail::appendObjFromScene(Scene &scene, const std::string &objPath, const Transform &toWorld,
                                const std::string &objectName, int defaultMaterial,
                                const std::string &defaultMaterialName, const InputLocation &fileFrom,
                                const InputLocation &materialFrom) {
  const std::string text = readInputFile(objPath, fileFrom, "OBJ file");
  ObjScan scan = scanObj(objPath, text);
  std::map<std::string, std::string> mtlTexts;
  std::map<std::string, MtlSource> mtlSources = scanMtlFiles(scan.mtlFiles, mtlTexts);

  // tinyobjloader parses the text read above, not the file again by name.
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> mtlMaterials;
  std::string parseWarning, parseError;
  {
    std::istringstream objStream(text);
    MtlTextReader mtlReader(fs::path(objPath).parent_path(), mtlTexts);
    const bool parsed = tinyobj::LoadObj(&attrib, &shapes, &mtlMaterials, &parseWarning, &parseError, &objStream,
                                         &mtlReader, /*triangulate=*/false,  // quads stay quads for the mesher
                                         /*default_vcols_fallback=*/false);
    if (!parsed || !parseError.empty()) fileError(objPath, lineInMessage(parseError), "OBJ parse error: " + parseError);
  }
  std::istringstream warnings(parseWarning);
  for (std::string w; std::getline(warnings, w);) {
    // Unknown usemtl names are resolved below (they may name JSON materials).
    if (w.empty() || w.find("not found in .mtl") != std::string::npos) continue;
    scene.warnings.push_back(objPath + ": " + w);
  }

  std::map<std::string, size_t> mtlByName;
  for (size_t i = 0; i < mtlMaterials.size(); ++i) mtlByName.emplace(mtlMaterials[i].name, i);

  // A name already in the scene (a JSON material, or an earlier file's) wins
  // over the MTL definition; MTL materials are converted on first use only.
  // resolve runs per face: findMaterial's scan of every name made 10⁵ usemtl materials quadratic.
  detail::MaterialNames materialNames(scene.materials);
  auto resolve = [&](const std::string &name) -> int {
    int index = materialNames.find(name);
    if (index >= 0) return index;
    auto it = mtlByName.find(name);
    if (it == mtlByName.end()) return -1;
    MtlSource source = mtlSources.count(name) ? mtlSources[name] : MtlSource{objPath, 0, 0, 0};
    scene.materials.push_back(convertMtlMaterial(mtlMaterials[it->second], source, scene.warnings));
    return static_cast<int>(scene.materials.size() - 1);
  };

  uint32_t fallbackMaterial;
  if (defaultMaterial >= 0) {
    fallbackMaterial = static_cast<uint32_t>(defaultMaterial);
  } else if (!defaultMaterialName.empty()) {
    int index = resolve(defaultMaterialName);
    if (index < 0) {
      std::vector<std::string> known;
      for (const Material &m : scene.materials) known.push_back(m.name);
      for (const auto &[name, i] : mtlByName) known.push_back(name);
      throw InputError(materialFrom, "material '" + defaultMaterialName +
                                         "' is defined neither in the scene's materials nor in the MTL of '" + objPath +
                                         "'" + didYouMean(defaultMaterialName, known));
    }
    fallbackMaterial = static_cast<uint32_t>(index);
  } else {
    fallbackMaterial = detail::defaultMaterialIndex(scene);
  }

  // Geometry: every OBJ vertex once, transformed into the world.
  const uint32_t positionOffset = static_cast<uint32_t>(scene.positions.size());
  const int32_t normalOffset = static_cast<int32_t>(scene.normals.size());
  const int32_t uvOffset = static_cast<int32_t>(scene.uvs.size() / 2);
  for (size_t i = 0; i + 2 < attrib.vertices.size(); i += 3) {
    scene.positions.push_back(toWorld.point(toVec3(attrib.vertices, i)));
    // validateScene checks the same, but could name only the file, not the line (nor the JSON entry placing it).
    if (!withinCoordinateRange(scene.positions.back()))
      fileError(objPath, i / 3 < scan.vertexLines.size() ? scan.vertexLines[i / 3] : 0,
                fmt::format("this vertex lies at ({:g}, {:g}, {:g}) m in the scene{}, more than {:g} m from the "
                            "origin; the ray tracer works in single precision",
                            scene.positions.back().x, scene.positions.back().y, scene.positions.back().z,
                            fileFrom.file == objPath ? "" : " (placed by " + fileFrom.toString() + ")",
                            kMaxCoordinateMetres));
  }
  for (size_t i = 0; i + 2 < attrib.normals.size(); i += 3)
    scene.normals.push_back(toWorld.normal(toVec3(attrib.normals, i)));
  for (size_t i = 0; i + 1 < attrib.texcoords.size(); i += 2) {
    scene.uvs.push_back(widen(attrib.texcoords[i]));
    scene.uvs.push_back(widen(attrib.texcoords[i + 1]));
  }

  size_t faceCount = 0;
  for (const tinyobj::shape_t &shape : shapes) faceCount += shape.mesh.num_face_vertices.size();
  if (faceCount != scan.faceMaterialName.size())
    fileError(objPath, 0,
              "read " + std::to_string(faceCount) + " faces but the file has " +
                  std::to_string(scan.faceMaterialName.size()) + " 'f' lines");

  const bool flip = toWorld.determinant() < 0;
  std::map<std::string, uint32_t> objectByGroup;
  std::map<std::string, int> unknownMaterialFaces;
  size_t faceNumber = 0;
  for (const tinyobj::shape_t &shape : shapes) {
    size_t next = 0;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f, ++faceNumber) {
      auto [groupIt, inserted] = objectByGroup.try_emplace(shape.name, static_cast<uint32_t>(scene.objects.size()));
      if (inserted) {
        std::string name = shape.name.empty() ? objectName : objectName + "/" + shape.name;
        std::string source = shape.name.empty() ? objPath : objPath + " (group '" + shape.name + "')";
        scene.objects.push_back(SceneObject{name, source});
      }
      const std::string &materialName = scan.faceMaterialName[faceNumber];
      uint32_t material = fallbackMaterial;
      if (!materialName.empty()) {
        int index = resolve(materialName);
        if (index >= 0)
          material = static_cast<uint32_t>(index);
        else
          ++unknownMaterialFaces[materialName];
      }
      std::vector<uint32_t> vertices;
      std::vector<int32_t> uvs, normals;
      for (unsigned k = 0; k < shape.mesh.num_face_vertices[f]; ++k, ++next) {
        const tinyobj::index_t &index = shape.mesh.indices[next];
        vertices.push_back(positionOffset + static_cast<uint32_t>(index.vertex_index));
        uvs.push_back(index.texcoord_index >= 0 ? uvOffset + index.texcoord_index : -1);
        normals.push_back(index.normal_index >= 0 ? normalOffset + index.normal_index : -1);
      }
      detail::addPolygon(scene, vertices, uvs, normals, material, groupIt->second, flip);
    }
  }
  for (const auto &[name, count] : unknownMaterialFaces)
    scene.warnings.push_back(objPath + ": usemtl '" + name + "' names no material in the scene or the MTL; " +
                             std::to_string(count) + " faces use the default material instead");
}

void appendObj(Scene &scene, const std::string &objPath, const Transform &toWorld, const std::string &objectName,
               int defaultMaterial) {
  InputLocation here{objPath, 0, 0, ""};
  detail::appendObjFromScene(scene, objPath, toWorld, objectName, defaultMaterial, "", here, here);
}

}  // namespace radiant
