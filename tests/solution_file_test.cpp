// The solution file's compact form (format 7, docs/solution-format.md): every
// solver's mesh is derived on reading rather than stored, and a mesh that
// cannot be derived bit for bit is stored in full and still reloads exactly.
#include "io/solution_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "fuzz_inputs.h"
#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"
#include "sanitizer.h"
#include "scene/load_scene.h"
#include "solution_file_checks.h"
#include "util/error.h"

namespace radiant {
namespace {

/// The content flags of a file's first pass: after the 36-byte header and the seven u32 counts.
uint32_t contentFlags(const std::string &path) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(36 + 7 * 4);
  uint32_t content = 0;
  in.read(reinterpret_cast<char *>(&content), sizeof content);
  return content;
}

constexpr uint32_t kGeometryStored = 1, kFacesStored = 2, kReflectanceStored = 8, kEmissionStored = 16,
                   kNodeIrradiancePooled = 1u << 11;

/// Written and read back; the content flags of the file.
uint32_t roundTrip(const Solution &s, const Scene &scene, Solution &back) {
  const std::string path = (std::filesystem::temp_directory_path() / "radiant-solution-file-test.rad").string();
  writeSolution(s, scene, path);
  const uint32_t content = contentFlags(path);
  back = readSolution(path, scene);
  std::filesystem::remove(path);
  return content;
}

TEST(SolutionFile, EverySolversMeshIsDerivedOnReading) {
  RADIANT_SKIP_UNDER_SANITIZER();  // five solves; the fuzz seeds cover these files under the sanitizers
  // If a mesh builder's arithmetic changed and solution_geometry.cpp did not
  // follow, the files would silently grow to the full geometry: this fails
  // instead. Each solver's file must also read back (solution_file_checks.h).
  const Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  const RayTracer tracer(scene);
  struct Case {
    const char *solver;
    int adaptiveRounds;
  };
  for (const Case &c : {Case{"gauss-seidel", 0}, Case{"progressive", 0}, Case{"stochastic", 0}, Case{"hierarchical", 0},
                        Case{"hierarchical-exact", 0}, Case{"gauss-seidel", 1}}) {
    SCOPED_TRACE(std::string(c.solver) + (c.adaptiveRounds ? " with an adaptive round" : ""));
    MeshOptions mesh;
    mesh.maxEdgeLength = 0.15;
    SolverOptions options;
    options.solver = c.solver;
    options.tolerance = 1e-2;
    options.adaptiveRounds = c.adaptiveRounds;
    options.maxElements = 3000;
    const Solution s = meshAndSolve(scene, tracer, mesh, options);
    Solution back;
    const uint32_t content = roundTrip(s, scene, back);
    EXPECT_EQ(content & (kGeometryStored | kReflectanceStored | kEmissionStored), 0u) << std::hex << content;
    // The stochastic solver's node irradiance (its direct light at the
    // nodes) is the same at every node of a pool: stored once per pool.
    if (std::string(c.solver) == "stochastic") {
      EXPECT_NE(content & kNodeIrradiancePooled, 0u) << std::hex << content;
    }
    test::expectSolutionReadBack(s, back);
  }
}

TEST(SolutionFile, TexturedAndTranslucentSolutionsReadBack) {
  RADIANT_SKIP_UNDER_SANITIZER();  // three solves
  // A texture's ρ̄ per element is derived too (averageDiffuse over the
  // element, as initialSolution takes it); τ and the light through a
  // translucent wall (hierarchical-exact's transmitted radiosity) are stored.
  struct Case {
    const char *scene, *solver;
    uint32_t mustStore;
  };
  constexpr uint32_t kTransmittanceStored = 64, kTransmittedStored = 128;
  for (const Case &c : {Case{"cornell-textured", "progressive", 0}, Case{"translucent-wall", "gauss-seidel", 64},
                        Case{"translucent-wall", "hierarchical-exact", 64 | 128}}) {
    SCOPED_TRACE(std::string(c.scene) + " " + c.solver);
    const Scene scene = loadScene(std::string(RADIANT_SOURCE_DIR "/scenes/") + c.scene + "/scene.json");
    const RayTracer tracer(scene);
    MeshOptions mesh;
    SolverOptions options;
    options.solver = c.solver;
    options.tolerance = 1e-2;
    options.maxElements = 3000;
    const Solution s = meshAndSolve(scene, tracer, mesh, options);
    Solution back;
    const uint32_t content = roundTrip(s, scene, back);
    EXPECT_EQ(content & (kGeometryStored | kReflectanceStored | kEmissionStored), 0u) << std::hex << content;
    EXPECT_EQ(content & (kTransmittanceStored | kTransmittedStored), c.mustStore) << std::hex << content;
    test::expectSolutionReadBack(s, back);
  }
}

TEST(SolutionFile, StoresWhatItCannotDerive) {
  // A mesh no builder made (one node moved by one ulp), a reflectance that is
  // not the material's, and faces without patch counts: each is stored, and
  // the solution reloads exactly (geometry) or as f32 (values).
  const Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  const RayTracer tracer(scene);
  MeshOptions mesh;
  mesh.maxEdgeLength = 0.2;
  SolverOptions options;
  options.solver = "progressive";
  options.tolerance = 1e-2;
  Solution s = meshAndSolve(scene, tracer, mesh, options);
  Solution back;
  ASSERT_EQ(roundTrip(s, scene, back) & (kGeometryStored | kFacesStored | kReflectanceStored), 0u);

  s.mesh.nodes[5].x = std::nextafter(s.mesh.nodes[5].x, 1e9);
  s.reflectance[3][1] *= 0.5;
  s.mesh.facePatchCount.clear();
  const uint32_t content = roundTrip(s, scene, back);
  EXPECT_EQ(content & (kGeometryStored | kFacesStored | kReflectanceStored),
            kGeometryStored | kFacesStored | kReflectanceStored)
      << std::hex << content;
  EXPECT_EQ(content & kEmissionStored, 0u);
  EXPECT_EQ(back.mesh.nodes[5].x, s.mesh.nodes[5].x);
  EXPECT_EQ(back.reflectance[3][1], double(float(s.reflectance[3][1])));
  EXPECT_TRUE(back.mesh.facePatchCount.empty());
  // The node values were computed from the original ρ; those read back from the new one.
  s.updateNodesAndErrors();
  test::expectSolutionReadBack(s, back);
}

TEST(SolutionFile, EveryCorruptByteIsRefusedOrRead) {
  // A small fuzzing campaign over the new format's every field: each byte of
  // each seed (fuzz/corpus/solution_file: the furnace solved by progressive,
  // hierarchical and hierarchical-exact, and stored-geometry.rad, its progressive
  // solution with one node moved by an ulp, so that the mesh is stored in
  // full, written once by the writer of this format) set to 0, 0xFF, 0x7F and its value
  // + 1, then every truncation, through the fuzz target's own feed (which reads
  // the file and then asks of it what a renderer asks). Each must be read or
  // refused with an InputError; a crash, a sanitizer report or another
  // exception fails. The fingerprint bytes are patched back by the feed.
  const fuzz::ScratchFolder folder("solution-file-bytes");
  const std::filesystem::path seeds = std::filesystem::path(RADIANT_SOURCE_DIR) / "fuzz/corpus/solution_file";
  size_t read = 0, refused = 0;
  for (const char *name : {"progressive.rad", "hierarchical.rad", "hierarchical-exact.rad", "stored-geometry.rad"}) {
    SCOPED_TRACE(name);
    const std::vector<uint8_t> seed = fuzz::readFileBytes((seeds / name).string());
    ASSERT_GT(seed.size(), 100u);
    auto feed = [&](std::span<const uint8_t> bytes, const std::string &what) {
      try {
        fuzz::feedSolutionFile(bytes, folder.path());
        ++read;
      } catch (const InputError &) {
        ++refused;
      } catch (const std::exception &e) {
        ADD_FAILURE() << what << ": not an InputError: " << e.what();
      }
    };
#if RADIANT_UNDER_SANITIZER
    const size_t stride = 16;  // every field still, at a sixteenth of the time
#else
    const size_t stride = 1;
#endif
    for (size_t at = 0; at < seed.size(); at += stride)
      for (int value : {0x00, 0xFF, 0x7F, (seed[at] + 1) & 0xFF}) {
        std::vector<uint8_t> bytes = seed;
        bytes[at] = uint8_t(value);
        feed(bytes, "byte " + std::to_string(at) + " = " + std::to_string(value));
      }
    for (size_t length = 0; length < seed.size(); length += stride)
      feed(std::span<const uint8_t>(seed.data(), length), "the first " + std::to_string(length) + " bytes");
  }
  EXPECT_GT(refused, 0u);
  EXPECT_GT(read, 0u);  // values changed within range read back
}

}  // namespace
}  // namespace radiant
