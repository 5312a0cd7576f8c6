// The solution file's compact form (format 7, docs/solution-format.md): every
// solver's mesh is derived on reading rather than stored, and a mesh that
// cannot be derived bit for bit is stored in full and still reloads exactly.
#include "io/solution_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"
#include "sanitizer.h"
#include "scene/load_scene.h"
#include "solution_file_checks.h"

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

constexpr uint32_t kGeometryStored = 1, kFacesStored = 2, kReflectanceStored = 8, kEmissionStored = 16;

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

}  // namespace
}  // namespace radiant
