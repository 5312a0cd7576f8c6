// The default solver (--solver auto) on tessellated models: its cost grows
// with the input no faster than linearly. The cost is counted, not timed:
// the rays a solve casts (shadow rays and form-factor rays of
// hierarchical-exact; the stochastic solver's rays and its gathers at the
// nodes), which is what its time follows on any machine.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "mesh/mesh.h"
#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"
#include "sanitizer.h"
#include "scene/load_scene.h"

namespace radiant {
namespace {

/// The Cornell box with a UV sphere of `segments` slices on its floor
/// (scenes/cornell-sphere-1m at another tessellation): segments²/2 faces.
Scene sphereInTheBox(int segments) {
  std::ifstream in(RADIANT_SOURCE_DIR "/scenes/cornell-sphere-1m/scene.json");
  std::stringstream text;
  text << in.rdbuf();
  const std::string json =
      std::regex_replace(text.str(), std::regex("\"segments\": *[0-9]+"), "\"segments\": " + std::to_string(segments));
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("radiant-auto-solver-" + std::to_string(::getpid()) + ".json");
  std::ofstream(path) << json;
  Scene scene = loadScene(path.string());
  std::filesystem::remove(path);
  return scene;
}

struct SolveCost {
  std::string solver;
  size_t faces = 0;
  size_t rays = 0;
};

SolveCost autoSolve(int segments) {
  const Scene scene = sphereInTheBox(segments);
  const RayTracer tracer(scene);
  SolverOptions options;  // auto, and every other default
  const Solution s = meshAndSolve(scene, tracer, MeshOptions{}, options);
  return {s.stats.solver, scene.faces.size(), s.stats.formFactorRays};
}

TEST(AutoSolver, CostGrowsAtMostLinearlyWithTheFacesOfATessellatedModel) {
  RADIANT_SKIP_UNDER_SANITIZER();
  // 10³ → 10⁴ faces (the threshold of auto lies between them), then
  // 3·10³ → 3·10⁴ (both stochastic). "At most linearly": the rays grow by no
  // more than the faces do, with half again for the mesh's own discreteness.
  for (const auto &[small, large] : {std::pair{44, 140}, std::pair{78, 246}}) {
    const SolveCost a = autoSolve(small), b = autoSolve(large);
    ASSERT_GT(a.rays, 0u);
    const double facesGrowth = double(b.faces) / double(a.faces), raysGrowth = double(b.rays) / double(a.rays);
    std::printf("%zu faces (%s): %zu rays; %zu faces (%s): %zu rays\n", a.faces, a.solver.c_str(), a.rays, b.faces,
                b.solver.c_str(), b.rays);
    EXPECT_GT(facesGrowth, 9.0);
    EXPECT_LE(raysGrowth, 1.5 * facesGrowth) << a.faces << " faces (" << a.solver << "): " << a.rays << " rays; "
                                             << b.faces << " faces (" << b.solver << "): " << b.rays << " rays";
  }
}

}  // namespace
}  // namespace radiant
