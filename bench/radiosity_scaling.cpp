// radiosity_scaling — how each radiosity solver's time and memory grow with the element count.
//
// Issue 3 asks which solver to use at which mesh size, and whether the default
// one reaches a 1% residual on the Cornell box in under a second on 2 cores.
// So this program, for every solver in solverRegistry() and one scene:
//
//   1. runs a ladder of meshes of about 300, 1000, 3000, 10000 and 30000
//      elements, from small to large, with the default tolerance (1e-3) and on
//      ONE thread, so the figures compare across machines. Uniform meshes
//      (gauss-seidel, progressive, stochastic) get the edge length whose
//      buildMesh() comes closest to each target. Hierarchical refines
//      adaptively down to about the mesh's element size, so it gets the same
//      edge lengths and its element count (the leaves) is an output; its cost
//      follows the link count, also printed. The 30000 rung is skipped when the two rungs before it
//      predict more than --max-seconds (default 60) for it; any rung is
//      skipped when the solver refuses the mesh (gauss-seidel stores the full
//      matrix and stops at 8000 elements);
//   2. fits time = c·n^k by least squares on log time against log elements
//      over each solver's ladder and prints k (2 for an n² algorithm);
//   3. times the default (SolverOptions' "auto", named by what it picks) and
//      every solver on the scene at 0.05 m elements to tolerance 1e-2 on 2
//      threads, against the 1 s target, and on 1 thread for the speed-up.
//      These few seconds run first, so a quiet moment on a shared machine
//      can be caught for them.
//
// Time is the wall time of solveRadiosity() alone (not meshing): the median
// of 3 solves when one takes under 2 s, else 1. Memory, from the first solve
// of each rung, in MB of resident memory: "retained" is VmRSS with the solved
// Solution alive less VmRSS before meshing (the Solution: mesh, per-element
// bands, hierarchical links); "peak" is VmHWM at the end less VmRSS before
// meshing (retained plus what the solver held only while solving, e.g.
// gauss-seidel's matrix). VmHWM is reset between rungs by writing 5 to
// /proc/self/clear_refs; where that fails the peak column is "-". Freed heap
// is handed back (malloc_trim) before each rung so one rung's free lists do
// not hide the next rung's growth.
//
// Usage: radiosity_scaling [scene.json] [--max-seconds S]      (docs/PERFORMANCE.md)
#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "bench_common.h"
#include "mesh/mesh.h"
#include "radiosity/solution.h"
#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"
#include "scene/load_scene.h"
#include "util/error.h"

using namespace radiant;

namespace {

constexpr double kElementTargets[] = {300, 1000, 3000, 10000, 30000};
constexpr double kOptionalFrom = 30000;      // rungs this large run only if predicted under --max-seconds
constexpr double kMedianBelowSeconds = 2.0;  // solves shorter than this are repeated 3 times
constexpr double kTargetMeshSize = 0.05;     // metres, for the 1%-residual figure
constexpr double kTargetSeconds = 1.0;       // issue 3: 1% residual in under 1 s on 2 cores

/// Resident memory in kB from /proc/self/status: "VmRSS" (now) or "VmHWM" (peak).
long statusKilobytes(const std::string &field) {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind(field + ":", 0) == 0) return std::atol(line.c_str() + field.size() + 1);
  return -1;
}

/// Resets VmHWM to the current RSS (Linux ≥ 4.0); false where not allowed.
bool resetPeakResident() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  clear.flush();
  return bool(clear);
}

/// The edge length (metres) whose uniform mesh comes closest to `target` elements:
/// the count falls monotonically (if in steps) with the edge length, so bisect on its log.
double meshSizeFor(const Scene &scene, double target) {
  auto countAt = [&](double size) {
    MeshOptions options;
    options.maxEdgeLength = size;
    return double(buildMesh(scene, options).elements.size());
  };
  double small = 1e-3, large = 1.0;  // metres: millions of elements to one per patch
  for (int step = 0; step < 40; ++step) {
    double middle = std::sqrt(small * large);
    (countAt(middle) > target ? small : large) = middle;
  }
  return std::abs(std::log(countAt(small) / target)) < std::abs(std::log(countAt(large) / target)) ? small : large;
}

struct Run {
  std::string solver;          // as SolveStats::solver: what "auto" picked
  double seconds = 0;          // median wall time of solveRadiosity
  size_t uniformElements = 0;  // of the mesh given to the solver (hierarchical: the finest it may refine to)
  size_t elements = 0, links = 0, shadowRays = 0;
  int iterations = 0, repeats = 0;
  double residual = 0, escapedFraction = 0;
  double retainedMB = -1, peakMB = -1;
};

/// Meshes at `meshSize`, solves (1 or 3 times) and measures; throws what the solver throws.
Run solveAt(const Scene &scene, const RayTracer &tracer, double meshSize, const SolverOptions &options) {
  Run run;
  std::vector<double> seconds;
  do {
    malloc_trim(0);
    const long residentBefore = statusKilobytes("VmRSS");
    const bool peakReset = resetPeakResident();
    MeshOptions meshOptions;
    meshOptions.maxEdgeLength = meshSize;
    Solution solution = initialSolution(scene, buildMesh(scene, meshOptions));
    run.uniformElements = solution.elementCount();
    auto start = std::chrono::steady_clock::now();
    solveRadiosity(tracer, solution, options);
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (seconds.size() == 1) {
      const SolveStats &stats = solution.stats;
      malloc_trim(0);  // what the solver freed is not retained, even if the allocator kept it
      run.retainedMB = (statusKilobytes("VmRSS") - residentBefore) / 1024.0;
      if (peakReset) run.peakMB = (statusKilobytes("VmHWM") - residentBefore) / 1024.0;
      run.solver = stats.solver;
      run.elements = solution.elementCount();
      run.links = solution.links.size();
      run.iterations = stats.iterations;
      run.residual = stats.residual;
      run.shadowRays = stats.formFactorRays;
      run.escapedFraction = stats.escapedPower.average() / stats.emittedPower.average();
    }
  } while (seconds.front() < kMedianBelowSeconds && seconds.size() < 3);
  std::sort(seconds.begin(), seconds.end());
  run.seconds = seconds[seconds.size() / 2];
  run.repeats = int(seconds.size());
  return run;
}

/// Least-squares slope of log y against log x: the k of y = c·x^k.
double fittedExponent(const std::vector<double> &x, const std::vector<double> &y) {
  const double n = double(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

void printRow(const char *solver, double meshSize, const Run &r, const std::string &verdict = "") {
  char peak[16] = "-";  // VmHWM could not be reset: no peak for this row alone
  if (r.peakMB >= 0) std::snprintf(peak, sizeof peak, "%.1f", r.peakMB);
  std::printf("%-18s %8.4f %8zu %8zu %8d %9.2g %7.2f%% %10.3g %9.3f %3d %9.1f %9s%s\n", solver, meshSize, r.elements,
              r.links, r.iterations, r.residual, 100 * r.escapedFraction, double(r.shadowRays), r.seconds, r.repeats,
              r.retainedMB, peak, verdict.empty() ? "" : ("  " + verdict).c_str());
}

}  // namespace

int main(int argc, char **argv) {
  std::string scenePath = "scenes/cornell-box/scene.json";
  double maxSeconds = 60;
  if (!bench::parseSceneAndNumber(argc, argv, "--max-seconds", "S", scenePath, maxSeconds)) return 2;

  try {
    const double loadBefore = bench::loadAverage();
    Scene scene = loadScene(scenePath);
    RayTracer tracer(scene);

    std::vector<double> meshSizes;
    for (double target : kElementTargets) meshSizes.push_back(meshSizeFor(scene, target));

    std::printf(
        "radiosity_scaling: %s, %zu triangles; ladder on 1 thread, tolerance %.0e, %d shadow rays per form "
        "factor\n",
        scenePath.c_str(), scene.triangles.size(), SolverOptions{}.tolerance, SolverOptions{}.visibilitySamples);
    std::printf("seconds: wall time of the solve, median of 'n' solves; MB: resident memory (see the header)\n");
    std::printf(
        "\nfirst, to tolerance 1e-2 at mesh size %.2f m; the target (< %.0f s) is for 2 threads, the 1-thread row "
        "shows the speed-up; default solver '%s'\n",
        kTargetMeshSize, kTargetSeconds, SolverOptions{}.solver.c_str());
    std::printf("%-18s %8s %8s %8s %8s %9s %8s %10s %9s %3s %9s %9s  %s\n", "solver", "mesh (m)", "elements", "links",
                "iter", "residual", "escaped", "rays", "seconds", "n", "retain MB", "peak MB", "threads, target");
    std::vector<std::string> solvers = {SolverOptions{}.solver};
    for (const SolverInfo &info : solverRegistry()) solvers.push_back(info.name);
    for (const std::string &solver : solvers)
      for (int threads : {1, 2}) {
        SolverOptions options;
        options.solver = solver;
        options.tolerance = 1e-2;
        options.threads = threads;
        Run run = solveAt(scene, tracer, kTargetMeshSize, options);
        std::string name = solver == run.solver ? solver : solver + "=" + run.solver;
        printRow(name.c_str(), kTargetMeshSize, run,
                 threads == 1                   ? "1"
                 : run.seconds < kTargetSeconds ? "2  PASS"
                                                : "2  FAIL");
        std::fflush(stdout);
      }
    std::printf("\nthe ladder, on 1 thread\n");
    std::printf("%-18s %8s %8s %8s %8s %9s %8s %10s %9s %3s %9s %9s\n", "solver", "mesh (m)", "elements", "links",
                "iter", "residual", "escaped", "rays", "seconds", "n", "retain MB", "peak MB");

    struct Exponents {
      std::string solver;
      double againstElements, againstLinks, linksAgainstElements;
    };
    std::vector<Exponents> exponents;
    for (const SolverInfo &info : solverRegistry()) {
      SolverOptions options;
      options.solver = info.name;
      options.threads = 1;
      std::vector<double> elements, uniformElements, links, seconds;
      bool refused = false;  // a solver that refuses a mesh refuses every finer one
      for (size_t rung = 0; rung < meshSizes.size(); ++rung) {
        const double meshSize = meshSizes[rung];
        if (refused) {
          std::printf("%-18s %8.4f   skipped: the solver refuses this mesh\n", info.name, meshSize);
          continue;
        }
        // The optional rung: extrapolate the last two rungs' growth, in the given mesh's count.
        if (kElementTargets[rung] >= kOptionalFrom && seconds.size() >= 2) {
          MeshOptions meshOptions;
          meshOptions.maxEdgeLength = meshSize;
          double uniform = double(buildMesh(scene, meshOptions).elements.size());
          size_t last = seconds.size() - 1;
          double slope =
              fittedExponent({uniformElements[last - 1], uniformElements[last]}, {seconds[last - 1], seconds[last]});
          double predicted = seconds[last] * std::pow(uniform / uniformElements[last], std::max(1.0, slope));
          if (predicted > maxSeconds) {
            std::printf("%-18s %8.4f   skipped: predicted %.0f s > --max-seconds %.0f\n", info.name, meshSize,
                        predicted, maxSeconds);
            continue;
          }
        }
        try {
          Run run = solveAt(scene, tracer, meshSize, options);
          printRow(info.name, meshSize, run);
          elements.push_back(double(run.elements));
          uniformElements.push_back(double(run.uniformElements));
          seconds.push_back(run.seconds);
          links.push_back(double(run.links));
        } catch (const InputError &) {
          std::printf("%-18s %8.4f   skipped: the solver refuses this mesh\n", info.name, meshSize);
          refused = true;
        }
        std::fflush(stdout);
      }
      if (elements.size() < 2) continue;
      Exponents fit{info.name, fittedExponent(elements, seconds), 0, 0};
      if (links.front() > 0) {  // hierarchical: the work is per link
        fit.againstLinks = fittedExponent(links, seconds);
        fit.linksAgainstElements = fittedExponent(elements, links);
      }
      exponents.push_back(fit);
    }

    std::printf("\nfitted time = c * elements^k over each ladder (least squares, log-log)\n");
    for (const Exponents &e : exponents) {
      std::printf("  %-13s k = %.2f", e.solver.c_str(), e.againstElements);
      if (e.againstLinks > 0)
        std::printf("   (time = c * links^%.2f; links = c * elements^%.2f)", e.againstLinks, e.linksAgainstElements);
      std::printf("\n");
    }

    std::printf("\nload average (1 min) %.2f before, %.2f after\n", loadBefore, bench::loadAverage());
  } catch (const std::exception &error) {
    std::fprintf(stderr, "radiosity_scaling: %s\n", error.what());
    return 1;
  }
  return 0;
}
