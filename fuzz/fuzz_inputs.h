// One input of each fuzz target, fed through the loaders the program uses
// (docs/fuzzing.md). Shared by the libFuzzer targets (fuzz/fuzz_*.cpp) and the
// regression test (tests/fuzz_regressions_test.cpp), so that a saved input is
// replayed exactly as the fuzzer ran it.
//
// The contract every loader keeps, and every feed checks by letting anything
// else escape: an input is either accepted or refused with radiant's
// InputError. Any other exception, a crash, a sanitizer report, a hang or an
// allocation beyond the fuzzer's -rss_limit_mb is a defect.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace radiant::fuzz {

/// A folder of one process's scratch files (the input under test, written as
/// the file the loader reads, and the fixtures scenes may name): created at
/// construction, removed with everything in it at destruction. Under
/// $RADIANT_FUZZ_SCRATCH when set, else /dev/shm when it exists (a campaign
/// then does not write to the disk), else the temporary folder.
class ScratchFolder {
 public:
  explicit ScratchFolder(const std::string &purpose);
  ~ScratchFolder();
  ScratchFolder(const ScratchFolder &) = delete;
  ScratchFolder &operator=(const ScratchFolder &) = delete;
  const std::string &path() const { return path_; }

 private:
  std::string path_;
};

/// The targets, by the name tools/fuzz.sh, the corpus folders
/// (fuzz/corpus/<name>/) and the regression folders
/// (tests/fuzz-regressions/<name>/) use.
struct FuzzTarget {
  const char *name;
  /// Feeds one input: writes it into `folder` as the file the loader reads
  /// and loads it. Returns normally when the input is accepted; throws
  /// InputError when it is refused; anything else is a finding.
  void (*feed)(std::span<const uint8_t> input, const std::string &folder);
  /// Where the feed writes the input (what a refusal's message should name).
  const char *fileName;
};

/// A JSON scene (scenes/*/scene.json), through loadScene: parsing, materials,
/// objects, OBJ files and textures it names (the folder holds the fixtures
/// writeFixtures puts there), validation.
void feedSceneJson(std::span<const uint8_t> input, const std::string &folder);

/// An OBJ file and its MTL, through loadScene on the OBJ (a bare OBJ scene).
/// The input is split at the first kMtlSeparator line: before it the OBJ,
/// after it the MTL, written as model.obj and model.mtl; the OBJ reads the MTL
/// only if it says `mtllib model.mtl`.
void feedObjMtl(std::span<const uint8_t> input, const std::string &folder);
inline constexpr const char *kMtlSeparator = "#--- model.mtl ---";

/// An image file, through Texture::load (PNG, JPEG, OpenEXR: recognised by
/// signature), then the texture's lookups (bilinear, trilinear, footprint
/// average, gradient), which read the mip-map pyramid built from it.
void feedTexture(std::span<const uint8_t> input, const std::string &folder);

/// A linear image, through readImage (what `radiant compare` and `tonemap`
/// read): written as image.exr when it starts with OpenEXR's signature, else
/// as image.pfm.
void feedImage(std::span<const uint8_t> input, const std::string &folder);

/// A solution file (docs/solution-format.md), through readSolutionPasses for
/// the furnace scene (scenes/furnace/scene.json), then read at the centre and
/// corners of every face as a renderer reads it (solution_query.h). The scene
/// fingerprint (bytes 24…31) is overwritten with the furnace's before the file
/// is written: a fuzzer cannot guess a 64-bit hash, and without it every
/// input would stop at the first check.
void feedSolutionFile(std::span<const uint8_t> input, const std::string &folder);

/// A photometric file (docs/luminaires.md#photometric-files), through
/// readPhotometricFile twice: written as lamp.ies (the IES LM-63 reader) and
/// as lamp.ldt (the EULUMDAT reader); the folder also holds the fixture
/// tilt.tlt, so that TILT=tilt.tlt reaches the tilt-file reader. An accepted
/// distribution is then asked what a renderer asks (candela, pdf and sample
/// towards a few directions, lumens, tiltFactor), and must give finite,
/// non-negative values, pdf > 0 where candela > 0 and unit sample
/// directions: else it throws std::logic_error, a finding. Since one input
/// is rarely both formats, the input counts as accepted when either reader
/// accepts it (the other's refusal is dropped), and as refused only when
/// both refuse it: then the IES reader's InputError is rethrown.
void feedPhotometry(std::span<const uint8_t> input, const std::string &folder);

/// A glTF 2.0 file, through loadScene (load_gltf.cpp, gltf_file.cpp): written
/// as model.glb when it starts with the GLB signature, else as model.gltf; the
/// JSON and GLB chunks, accessors, buffer views, data: URIs, and the fixtures
/// buffer.bin (one triangle's positions) and textures/checker.png as external
/// files.
void feedGltf(std::span<const uint8_t> input, const std::string &folder);

/// An MGF file, through loadScene (load_mgf.cpp, mgf_geometry.cpp,
/// mgf_material.cpp): written as scene.mgf; includes (the fixture part.mgf,
/// and the file itself), transforms and arrays, and `ies isotropic.ies`.
void feedMgf(std::span<const uint8_t> input, const std::string &folder);

/// A Radiance RGBE image, through readImage: written as image.hdr.
void feedHdr(std::span<const uint8_t> input, const std::string &folder);

/// All targets, in the order tools/fuzz.sh runs them.
std::span<const FuzzTarget> fuzzTargets();

/// Writes the files a fuzzed scene may name into `folder`, under the names
/// scenes/cornell-textured uses: textures/checker.png (8-bit RGB) and
/// textures/egg-crate.png (16-bit), both 8 × 8, and mesh.obj with mesh.mtl
/// (a quad with a texture and a bump map); and tilt.tlt, an IES tilt file of
/// three angles (for TILT=tilt.tlt). Called once per folder.
void writeFixtures(const std::string &folder);

/// The file's bytes.
std::vector<uint8_t> readFileBytes(const std::string &path);

}  // namespace radiant::fuzz
