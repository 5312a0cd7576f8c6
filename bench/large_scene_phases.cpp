// The phases of `radiant render --method interpolate` on a large scene, each
// timed: loading, the ray tracer's BVH, cutting faces where surfaces meet
// (mesh/face_split.h), meshing, the stochastic solve, the image. Issue 20's
// target: a 10⁶-triangle scene in ≤ 30 s on 2 cores (docs/PERFORMANCE.md).
//
//   build/large_scene_phases [scene.json] [--runs N]
//   (default: scenes/cornell-sphere-1m/scene.json, 1 run; medians over runs)
#include <fmt/format.h>

#include <map>

#include "bench_common.h"
#include "mesh/face_split.h"
#include "mesh/mesh.h"
#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"
#include "render/driver.h"
#include "render/registry.h"
#include "scene/load_scene.h"

using namespace radiant;

int main(int argc, char **argv) {
  std::string scenePath = std::string(RADIANT_BENCH_SOURCE_DIR) + "/scenes/cornell-sphere-1m/scene.json";
  double runs = 1;
  if (!bench::parseSceneAndNumber(argc, argv, "--runs", "N", scenePath, runs)) return 2;
  const std::vector<std::string> phases = {"load", "bvh", "cut faces", "mesh", "solve", "image", "total"};
  std::map<std::string, std::vector<double>> seconds;
  size_t triangles = 0, elements = 0;
  for (int run = 0; run < int(runs); ++run) {
    auto start = std::chrono::steady_clock::now(), phaseStart = start;
    auto lap = [&](const std::string &phase) {
      seconds[phase].push_back(bench::secondsSince(phaseStart));
      phaseStart = std::chrono::steady_clock::now();
    };
    Scene scene = loadScene(scenePath);
    lap("load");
    RayTracer tracer(scene);
    triangles = scene.triangles.size();
    lap("bvh");
    const std::vector<FaceSplit> splits = splitFaces(scene, tracer);
    lap("cut faces");
    MeshOptions meshOptions;
    meshOptions.faceSplits = &splits;
    Solution solution = initialSolution(scene, buildMesh(scene, meshOptions));
    elements = solution.elementCount();
    lap("mesh");
    SolverOptions options;
    options.solver = "stochastic";
    solveRadiosity(tracer, solution, options);
    lap("solve");
    RenderContext context;
    context.solution = &solution;
    const auto renderer = createRenderer("interpolate", tracer, context, ParameterValues{});
    Film film(scene.render.width, scene.render.height);
    DriverOptions driver;
    driver.samplesPerPixel = scene.render.samplesPerPixel;
    renderImage(PinholeCamera(scene.camera, scene.render.width, scene.render.height), *renderer, driver, film);
    lap("image");
    seconds["total"].push_back(bench::secondsSince(start));
  }
  fmt::print("{}: {} triangles, {} elements, {} run(s), load average {:.1f}\n", scenePath, triangles, elements,
             int(runs), bench::loadAverage());
  for (const std::string &phase : phases) fmt::print("  {:<10} {:7.2f} s\n", phase, bench::median(seconds[phase]));
}
