// multipass_budget — how much of its time budget a multipass render uses.
//
// Multipass (render/multipass.h) runs passes until `--time` is spent: the
// preview and the high-frequency pass, then passes of control or paired
// samples whose lengths are planned from the times measured so far, the last
// one shortened so that no sliver of a pass is left. A render should
// therefore end close to its budget: well before it wastes what was paid for
// (a pass too short for one sample once ended renders early), well after it
// overruns (a planned pass that does not fit). This depends on the machine's
// speed, so it is measured here rather than tested (the tests check the
// schedule where speed cannot matter: tests/multipass_test.cpp,
// Multipass.ASpentBudgetEndsTheRenderAfterThePreview and
// Multipass.ABudgetNotSpentRunsToTheSampleCap).
//
// For each budget (--budgets, default 1,2,5 s), --repeats times (default 3,
// seeds 1..N), renderMultipass() renders the scene (default the specular
// Cornell box, whose glass and mirror give every pass its caustic map) at
// --size² pixels (default 64) on --threads (default 2), solving as `radiant
// render --method multipass` does: an interrupted progressive solution for the
// preview, --solver (default auto) for the later passes, on the default mesh,
// solving time counted in the budget. With no sample cap, only the budget ends
// the render; a budget shorter than the preview, the solve and pass 2
// together is overrun by the difference, whatever the schedule does after.
// It prints, as medians of the repeats, the wall time renderMultipass took
// and its ratio to the budget, the time to the end of pass 2 (the fixed part),
// the number of passes, the length of the last one, and the samples per pixel
// reading the solution and paired among them. The load average is printed
// before and after (docs/PERFORMANCE.md: the machine is shared).
//
// Usage: multipass_budget [scene.json] [--budgets 1,2,5] [--repeats 3] [--size 64] [--threads 2] [--solver auto]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <string>
#include <vector>

#include "bench_common.h"
#include "mesh/mesh.h"
#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"
#include "render/multipass.h"
#include "scene/camera.h"
#include "scene/load_scene.h"

using namespace radiant;
using radiant::bench::median;
using radiant::bench::secondsSince;

namespace {

/// Far more than any budget here fills: the budget alone ends the render.
constexpr int kUncappedSamplesPerPixel = 1 << 24;

struct Run {
  double seconds = 0, fixedSeconds = 0, lastPassSeconds = 0;
  int passes = 0, controlSamples = 0, pairedSamples = 0;
};

void printUsage(const char *program) {
  std::fprintf(stderr,
               "usage: %s [scene.json] [--budgets 1,2,5] [--repeats 3] [--size 64] [--threads 2] [--solver auto]\n",
               program);
}

}  // namespace

int main(int argc, char **argv) {
  std::string scenePath = "scenes/cornell-specular/scene.json", budgetList = "1,2,5", solverName = "auto";
  int repeats = 3, size = 64, threads = 2;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if (arg == "--budgets" && hasValue)
      budgetList = argv[++i];
    else if (arg == "--repeats" && hasValue)
      repeats = std::atoi(argv[++i]);
    else if (arg == "--size" && hasValue)
      size = std::atoi(argv[++i]);
    else if (arg == "--threads" && hasValue)
      threads = std::atoi(argv[++i]);
    else if (arg == "--solver" && hasValue)
      solverName = argv[++i];
    else if (arg.rfind("--", 0) == 0)
      return printUsage(argv[0]), 2;
    else
      scenePath = arg;
  }
  std::vector<double> budgets;
  std::stringstream list(budgetList);
  for (std::string item; std::getline(list, item, ',');) budgets.push_back(std::atof(item.c_str()));
  if (budgets.empty() || repeats < 1 || size < 1) return printUsage(argv[0]), 2;

  try {
    const double loadBefore = bench::loadAverage();
    const Scene scene = loadScene(scenePath);
    RayTracer tracer(scene);
    PinholeCamera camera(scene.camera, size, size);
    std::printf(
        "multipass_budget: %s, %dx%d, %d threads, solver %s (%s here), medians of %d runs; load average %.2f "
        "before\n\n",
        scenePath.c_str(), size, size, threads, solverName.c_str(),
        [&] {
          SolverOptions options;
          options.solver = solverName;
          return chooseSolver(scene, options).solver;
        }()
            .c_str(),
        repeats, loadBefore);
    std::printf("| budget s | used s | used / budget | passes 1-2 s | passes | last pass s | R spp | pairs |\n");
    std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (double budget : budgets) {
      std::vector<Run> runs;
      for (int repeat = 1; repeat <= repeats; ++repeat) {
        MultipassOptions options;
        options.timeBudgetSeconds = budget;
        options.samplesPerPixel = kUncappedSamplesPerPixel;
        options.seed = uint64_t(repeat);
        options.threads = threads;
        auto solve = [&](int maxShots) {  // as the command line: the preview progressive, then --solver
          SolverOptions solver;
          solver.solver = maxShots > 0 ? "progressive" : multipassSolverName(solverName, budget);
          solver.seed = uint64_t(repeat);
          solver.threads = threads;
          if (maxShots > 0) solver.maxIterations = maxShots;
          return meshAndSolve(scene, tracer, MeshOptions{}, solver);
        };
        Run run;
        const auto start = std::chrono::steady_clock::now();
        renderMultipass(tracer, camera, size, size, options, solve,
                        [&](const MultipassPass &pass, const Image &, const Image &) {
                          if (pass.index <= 2)
                            run.fixedSeconds = secondsSince(start);  // pass 2 is skipped under short budgets
                          run.passes = pass.index, run.lastPassSeconds = pass.seconds;
                          run.controlSamples = pass.controlSamples, run.pairedSamples = pass.pairedSamples;
                        });
        run.seconds = secondsSince(start);
        std::fprintf(stderr, "[%g s] run %d/%d: %.3f s (%.3f of the budget), %d passes, last %.3f s\n", budget, repeat,
                     repeats, run.seconds, run.seconds / budget, run.passes, run.lastPassSeconds);
        runs.push_back(run);
      }
      auto medianOf = [&](auto field) {
        std::vector<double> values;
        for (const Run &run : runs) values.push_back(double(field(run)));
        return median(values);
      };
      const double used = medianOf([](const Run &r) { return r.seconds; });
      std::printf("| %g | %.3f | %.3f | %.3f | %g | %.3f | %g | %g |\n", budget, used, used / budget,
                  medianOf([](const Run &r) { return r.fixedSeconds; }),
                  medianOf([](const Run &r) { return r.passes; }),
                  medianOf([](const Run &r) { return r.lastPassSeconds; }),
                  medianOf([](const Run &r) { return r.controlSamples; }),
                  medianOf([](const Run &r) { return r.pairedSamples; }));
      std::fflush(stdout);
    }
    std::printf("\nload average %.2f after\n", bench::loadAverage());
  } catch (const std::exception &error) {
    std::fprintf(stderr, "multipass_budget: %s\n", error.what());
    return 1;
  }
  return 0;
}
