// reichert's cost per sample against the element count (issue 37: it must
// follow the cut of the elements' tree, not their number). The Cornell box
// meshed at element edges giving about 2·10³, 3·10⁴ (16×) and 5·10⁵ (256×)
// elements, each with the same made-up light field (emission plus a uniform
// reflected radiosity: the cost of the cut depends on where the power is,
// not on a solve), rendered at 64×64, 2 samples per pixel, one thread. Prints
// the median time per sample of the gather (every sample gathers:
// --gather-chance 1) and its ratio to the coarsest mesh, beside the gather
// over every element (--cut-error 0) on the coarsest, and the time per sample
// with the default --gather-chance (most samples read the solution).
//
//   build/reichert_scaling [scene.json] [--repeats 3]     (from the repository root)
#include <fmt/format.h>

#include <cstdio>

#include "bench_common.h"
#include "mesh/mesh.h"
#include "radiosity/solution.h"
#include "raytrace/ray_tracer.h"
#include "render/driver.h"
#include "render/registry.h"
#include "scene/camera.h"
#include "scene/load_scene.h"
#include "util/parameters.h"

using namespace radiant;

namespace {

double secondsPerSample(const Scene &scene, const RayTracer &tracer, const Solution &solution, double cutError,
                        const char *gatherChance, int repeats) {
  RenderContext context;
  context.solution = &solution;
  ParameterValues parameters;
  parameters.set("cut-error", fmt::format("{}", cutError), InputLocation{"bench"});
  if (gatherChance) parameters.set("gather-chance", gatherChance, InputLocation{"bench"});
  auto renderer = createRenderer("reichert", tracer, context, parameters);
  constexpr int kSize = 64, kSamples = 2;
  const PinholeCamera camera(scene.camera, kSize, kSize);
  std::vector<double> seconds;
  for (int r = 0; r < repeats; ++r) {
    DriverOptions driver;
    driver.samplesPerPixel = kSamples;
    driver.threads = 1;
    driver.stopConvergedPixels = false;
    Film film(kSize, kSize);
    const auto start = std::chrono::steady_clock::now();
    renderImage(camera, *renderer, driver, film);
    seconds.push_back(bench::secondsSince(start) / (kSize * kSize * kSamples));
  }
  return bench::median(seconds);
}

}  // namespace

int main(int argc, char **argv) {
  std::string scenePath = "scenes/cornell-box/scene.json";
  double repeats = 3;
  if (!bench::parseSceneAndNumber(argc, argv, "--repeats", "N", scenePath, repeats)) return 2;
  const Scene scene = loadScene(scenePath);
  const RayTracer tracer(scene);
  fmt::print("reichert on {} at 64x64, 2 spp, 1 thread (load {:.2f}), medians of {:g} runs\n", scenePath,
             bench::loadAverage(), repeats);
  fmt::print("{:>9} {:>10} {:>17} {:>8} {:>21}\n", "elements", "cut-error", "gather µs/sample", "ratio",
             "default µs/sample");
  double first = 0;
  bool everyElementDone = false;
  for (double edge : {0.05, 0.0125, 0.003125}) {
    MeshOptions options;
    options.maxEdgeLength = edge;
    Solution solution = initialSolution(scene, buildMesh(scene, options));
    for (size_t e = 0; e < solution.elementCount(); ++e)
      solution.radiosity[e] = solution.emission[e] + solution.reflectance[e] * Bands(0.3);
    solution.updateNodesAndErrors();
    const double perSample = secondsPerSample(scene, tracer, solution, 0.02, "1", int(repeats));
    const double byDefault = secondsPerSample(scene, tracer, solution, 0.02, nullptr, int(repeats));
    if (first == 0) first = perSample;
    fmt::print("{:>9} {:>10} {:>17.1f} {:>8.2f} {:>21.1f}\n", solution.elementCount(), 0.02, 1e6 * perSample,
               perSample / first, 1e6 * byDefault);
    if (!everyElementDone) {
      const double every = secondsPerSample(scene, tracer, solution, 0, "1", 1);
      fmt::print("{:>9} {:>10} {:>17.1f} {:>8.2f}\n", solution.elementCount(), "0 (every)", 1e6 * every, every / first);
      everyElementDone = true;
    }
    std::fflush(stdout);
  }
  return 0;
}
