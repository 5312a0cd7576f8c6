#include "fuzz_inputs.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string_view>

#include "io/image.h"
#include "io/solution_file.h"
#include "radiosity/solution_query.h"
#include "scene/load_scene.h"
#include "scene/photometry.h"
#include "texture/texture.h"

#ifndef RADIANT_SOURCE_DIR
#error "RADIANT_SOURCE_DIR must name the repository (the fixtures and the furnace scene come from it)"
#endif

namespace radiant::fuzz {

namespace fs = std::filesystem;

namespace {

void writeFile(const std::string &path, const void *data, size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(static_cast<const char *>(data), std::streamsize(size));
  out.close();
  // Not an InputError: a full /dev/shm is the harness's failure, not the input's refusal.
  if (!out) throw std::runtime_error("fuzz harness: cannot write " + path);
}

void writeFile(const std::string &path, std::string_view text) {
  writeFile(path, text.data(), text.size());
}

std::string inFolder(const std::string &folder, const char *name) {
  return (fs::path(folder) / name).string();
}

/// The fixtures a scene may name, once per folder (writing them per input
/// would cost more than most inputs take to load).
void ensureFixtures(const std::string &folder) {
  static std::string written;
  if (written == folder) return;
  writeFixtures(folder);
  written = folder;
}

}  // namespace

ScratchFolder::ScratchFolder(const std::string &purpose) {
  std::error_code error;
  const char *chosen = std::getenv("RADIANT_FUZZ_SCRATCH");  // tools/fuzz.sh: one folder per campaign
  const fs::path base = chosen && *chosen                     ? fs::path(chosen)
                        : fs::is_directory("/dev/shm", error) ? fs::path("/dev/shm")
                                                              : fs::temp_directory_path();
  std::string pattern = (base / ("radiant-" + purpose + "-XXXXXX")).string();
  if (!::mkdtemp(pattern.data())) throw std::runtime_error("fuzz harness: cannot create " + pattern);
  path_ = pattern;
}

ScratchFolder::~ScratchFolder() {
  std::error_code ignored;
  fs::remove_all(path_, ignored);
}

std::vector<uint8_t> readFileBytes(const std::string &path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

void writeFixtures(const std::string &folder) {
  fs::create_directories(fs::path(folder) / "textures");
  // 8 × 8 texels: a scene that names them costs little to load, input after input.
  constexpr int kSize = 8;
  std::vector<unsigned char> checker;
  std::vector<uint16_t> heights;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const unsigned char code = (x / 2 + y / 2) % 2 ? 230 : 25;
      checker.insert(checker.end(), {code, code, code});
      const auto height = static_cast<uint16_t>(65535 * (x * kSize + y) / (kSize * kSize - 1));
      heights.insert(heights.end(), {height, height, height});
    }
  writePngBytes(checker, kSize, kSize, inFolder(folder, "textures/checker.png"));
  writePng16(heights, kSize, kSize, inFolder(folder, "textures/egg-crate.png"));
  writeFile(inFolder(folder, "mesh.obj"),
            "mtllib mesh.mtl\n"
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
            "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
            "vn 0 0 1\n"
            "usemtl checker\n"
            "f 1/1/1 2/2/1 3/3/1 4/4/1\n");
  writeFile(inFolder(folder, "mesh.mtl"),
            "newmtl checker\n"
            "Kd 0.8 0.8 0.8\n"
            "map_Kd textures/checker.png\n"
            "bump -bm 0.01 textures/egg-crate.png\n");
  // An IES tilt file (lamp-to-luminaire geometry, count, angles, factors).
  writeFile(inFolder(folder, "tilt.tlt"), "1\n3\n0 45 90\n1 0.9 0.8\n");
  // A glTF buffer of one triangle's three float positions (uri "buffer.bin").
  const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  writeFile(inFolder(folder, "buffer.bin"), triangle, sizeof triangle);
  // An MGF file to include (i part.mgf) and an isotropic IES file for MGF's ies entity.
  writeFile(inFolder(folder, "part.mgf"), "v a =\n p 0 0 0\nv b =\n p 1 0 0\nv c =\n p 0 1 0\nf a b c\n");
  writeFile(inFolder(folder, "isotropic.ies"),
            "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 180\n0\n100 100\n");
}

namespace {

/// The input written as `name` beside the fixtures, then loaded as a scene.
void loadSceneNamed(std::span<const uint8_t> input, const std::string &folder, const char *name) {
  ensureFixtures(folder);
  const std::string path = inFolder(folder, name);
  writeFile(path, input.data(), input.size());
  loadScene(path);
}

}  // namespace

void feedSceneJson(std::span<const uint8_t> input, const std::string &folder) {
  loadSceneNamed(input, folder, "scene.json");
}

void feedObjMtl(std::span<const uint8_t> input, const std::string &folder) {
  ensureFixtures(folder);
  const std::string_view text(reinterpret_cast<const char *>(input.data()), input.size());
  // The separator on a line of its own (or the input's first line).
  const std::string separator = std::string(kMtlSeparator) + "\n";
  size_t at = text.rfind(separator, 0) == 0 ? 0 : text.find("\n" + separator);
  std::string_view obj = text, mtl;
  if (at != std::string_view::npos) {
    const size_t mtlStart = at + (at == 0 ? 0 : 1) + separator.size();
    obj = text.substr(0, at == 0 ? 0 : at + 1);
    mtl = text.substr(mtlStart);
  }
  const std::string objPath = inFolder(folder, "model.obj");
  writeFile(objPath, obj);
  writeFile(inFolder(folder, "model.mtl"), mtl);
  loadScene(objPath);
}

void feedTexture(std::span<const uint8_t> input, const std::string &folder) {
  const std::string path = inFolder(folder, "texture");
  writeFile(path, input.data(), input.size());
  const Texture texture = Texture::load(path, TextureEncoding::Colour, TextureWrap::Repeat);
  // What the renderers and the solver ask of a texture, at points and
  // footprints that reach past its edges and down its mip-map pyramid.
  static constexpr std::array<std::array<double, 2>, 3> kTriangle{{{-0.3, -0.2}, {1.4, 0.1}, {0.5, 1.7}}};
  volatile double sink = texture.mean()[0];
  sink = sink + texture.bilinear(0.3, 0.7)[0] + texture.bilinear(-2.5, 7.25)[1];
  sink = sink + texture.filtered(0.6, 0.1, 0.0)[0] + texture.filtered(0.6, 0.1, 0.3)[1] +
         texture.filtered(0.6, 0.1, 10.0)[2];
  sink = sink + texture.average(kTriangle)[0];
  sink = sink + texture.gradient(0.25, 0.75)[0];
}

void feedImage(std::span<const uint8_t> input, const std::string &folder) {
  static constexpr std::array<uint8_t, 4> kExrSignature{0x76, 0x2F, 0x31, 0x01};
  const bool exr = input.size() >= 4 && std::equal(kExrSignature.begin(), kExrSignature.end(), input.begin());
  const std::string path = inFolder(folder, exr ? "image.exr" : "image.pfm");
  writeFile(path, input.data(), input.size());
  const Image image = readImage(path);
  volatile float sink = image.rgb.empty() ? 0.0f : image.rgb.back();
  static_cast<void>(sink);
}

namespace {

const Scene &furnaceScene() {
  static const Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/furnace/scene.json");
  return scene;
}

/// Reads the solution where a renderer would: points on every face that has
/// a patch, both reconstructions, the node fields and the links' index.
void readLikeARenderer(const Solution &solution, const Scene &scene) {
  const RadiosityMesh &mesh = solution.mesh;
  volatile double sink = 0;
  for (uint32_t f = 0; f < scene.faces.size(); ++f) {
    if (mesh.patchOfFace[f] < 0) continue;
    const Face &face = scene.faces[f];
    Vec3 centre{0, 0, 0};
    for (int k = 0; k < face.vertexCount; ++k) centre = centre + scene.positions[face.vertices[k]];
    centre = centre * (1.0 / face.vertexCount);
    std::vector<Vec3> points{centre};
    for (int k = 0; k < face.vertexCount; ++k)
      points.push_back(centre + (scene.positions[face.vertices[k]] - centre) * 0.99);
    for (const Vec3 &p : points)
      for (Reconstruction reconstruction : {Reconstruction::Interpolated, Reconstruction::Constant}) {
        SolutionPoint point;
        point.location = mesh.locate(f, p);
        point.reconstruction = reconstruction;
        sink = sink + radiosity(solution, point)[0] + reflectedRadiosity(solution, point)[1];
        sink = sink + textureFactor(solution, point.location, Bands(0.5), reconstruction)[2];
        sink = sink + errorEstimate(solution, point);
        if (solution.hasNodeIrradiance())
          sink = sink + fieldRadiance(solution, nodeField(solution, Field::Direct), point)[0];
      }
  }
  if (isHierarchical(solution)) {
    const LinksByReceiver index = indexLinksByReceiver(solution);
    for (uint32_t e = 0; e < mesh.elements.size(); ++e)
      forEachLinkLighting(solution, index, e, [&](const Link &link) { sink = sink + link.formFactor; });
  }
}

}  // namespace

void feedSolutionFile(std::span<const uint8_t> input, const std::string &folder) {
  const Scene &scene = furnaceScene();
  std::vector<uint8_t> bytes(input.begin(), input.end());
  // Magic (16 bytes), version (u32), band count (u32), then the fingerprint (u64).
  constexpr size_t kFingerprintOffset = 24;
  if (bytes.size() >= kFingerprintOffset + 8) {
    const uint64_t fingerprint = sceneFingerprint(scene);
    std::memcpy(bytes.data() + kFingerprintOffset, &fingerprint, sizeof fingerprint);
  }
  const std::string path = inFolder(folder, "solution.rad");
  writeFile(path, bytes.data(), bytes.size());
  for (const Solution &solution : readSolutionPasses(path, scene)) readLikeARenderer(solution, scene);
}

namespace {

/// What an accepted distribution must satisfy; a logic_error (not an
/// InputError) when it does not, which the fuzz target reports and the
/// regression test fails on.
void require(bool condition, const std::string &file, const char *what) {
  if (!condition) throw std::logic_error("fuzz: accepted photometric file " + file + " gives " + what);
}

/// Asks of the distribution what a renderer asks: candela and pdf towards a
/// few directions, samples, the flux, the tilt factor.
void checkDistribution(const PhotometricDistribution &d) {
  static constexpr std::array<Vec3, 5> kDirections{{{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}, {0.3, -0.4, 0.866}}};
  const std::string &file = d.file();
  require(std::isfinite(d.lumens()) && d.lumens() >= 0, file, "a flux that is negative or not finite");
  require(std::isfinite(d.maxCandela()) && d.maxCandela() >= 0, file,
          "a largest intensity that is negative or not finite");
  for (double degrees : {0.0, 30.0, 90.0, 180.0})
    require(std::isfinite(d.tiltFactor(degrees)), file, "a tilt factor that is not finite");
  for (const Vec3 &w : kDirections) {
    const double candela = d.candela(w), pdf = d.pdf(w);
    require(std::isfinite(candela) && candela >= 0, file, "an intensity that is negative or not finite");
    require(std::isfinite(pdf) && pdf >= 0, file, "a pdf that is negative or not finite");
    require(candela == 0 || pdf > 0, file, "pdf 0 where the intensity is not");
  }
  for (double u : {0.0, 0.25, 0.5, 0.999999}) {
    double pdf = 0;
    const Vec3 w = d.sample(u, 1 - u, pdf);
    require(std::isfinite(pdf) && pdf >= 0, file, "a sample whose pdf is negative or not finite");
    require(pdf == 0 || std::abs(length(w) - 1) < 1e-9, file, "a sample direction that is not a unit vector");
  }
}

}  // namespace

void feedPhotometry(std::span<const uint8_t> input, const std::string &folder) {
  ensureFixtures(folder);
  std::exception_ptr firstRefusal;
  bool accepted = false;
  for (const char *name : {"lamp.ies", "lamp.ldt"}) {
    const std::string path = inFolder(folder, name);
    writeFile(path, input.data(), input.size());
    try {
      checkDistribution(*readPhotometricFile(path));
      accepted = true;
    } catch (const InputError &) {
      if (!firstRefusal) firstRefusal = std::current_exception();
    }
  }
  if (!accepted) std::rethrow_exception(firstRefusal);
}

void feedGltf(std::span<const uint8_t> input, const std::string &folder) {
  const bool glb = input.size() >= 4 && std::memcmp(input.data(), "glTF", 4) == 0;
  loadSceneNamed(input, folder, glb ? "model.glb" : "model.gltf");
}

void feedMgf(std::span<const uint8_t> input, const std::string &folder) {
  loadSceneNamed(input, folder, "scene.mgf");
}

void feedHdr(std::span<const uint8_t> input, const std::string &folder) {
  const std::string path = inFolder(folder, "image.hdr");
  writeFile(path, input.data(), input.size());
  const Image image = readImage(path);
  volatile float sink = image.rgb.empty() ? 0.0f : image.rgb.back();
  static_cast<void>(sink);
}

std::span<const FuzzTarget> fuzzTargets() {
  static constexpr FuzzTarget kTargets[] = {
      {"scene_json", feedSceneJson, "scene.json"},
      {"obj_mtl", feedObjMtl, "model.obj"},
      {"texture", feedTexture, "texture"},
      {"image", feedImage, "image."},
      {"solution_file", feedSolutionFile, "solution.rad"},
      {"photometry", feedPhotometry, "lamp.ies"},
      {"gltf", feedGltf, "model."},
      {"mgf", feedMgf, "scene.mgf"},
      {"hdr", feedHdr, "image.hdr"},
  };
  return kTargets;
}

}  // namespace radiant::fuzz
