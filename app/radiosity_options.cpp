#include "radiosity_options.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "mesh/mesh.h"
#include "radiosity/solver.h"
#include "util/error.h"
#include "util/interrupt.h"

namespace radiant {

void addRadiosityOptions(CLI::App &app, RadiosityCommandOptions &o) {
  std::string solvers = fmt::format("\n  {:<13} {}", "auto", kAutoSolverSummary);
  for (const SolverInfo &info : solverRegistry()) solvers += fmt::format("\n  {:<13} {}", info.name, info.summary);
  o.solverOption = app.add_option("--solver", o.solver, "Radiosity solver:" + solvers)->default_val("auto");
  // The parameters every solver takes first, then each solver's own.
  static ParameterTable common;
  const char *names[] = {"auto", "hierarchical-exact", "stochastic", "gauss-seidel", "progressive", "hierarchical"};
  if (common.empty())
    for (const ParameterSpec &spec : solverParameters("auto")) {
      bool everywhere = true;
      for (const char *name : names) {
        const ParameterTable &table = solverParameters(name);
        everywhere &=
            std::any_of(table.begin(), table.end(), [&](const ParameterSpec &s) { return s.name == spec.name; });
      }
      if (everywhere) common.push_back(spec);
    }
  std::vector<ParameterGroup> groups = {{"radiosity, every --solver", &common}};
  for (const char *name : names) groups.push_back({fmt::format("--solver {}", name), &solverParameters(name)});
  o.parameters.add(app, groups);
}

void checkRadiosityOptions(const RadiosityCommandOptions &options, bool solving, const std::string &reason) {
  const ParameterValues given = options.parameters.given();
  if (!solving) {
    if (options.solverOption->count() > 0) throw InputError(InputLocation{"--solver"}, "has no effect here: " + reason);
    if (!given.all().empty()) throw InputError(given.all().begin()->second.origin, "has no effect here: " + reason);
    return;
  }
  checkSolverParameters(options.solver, given);
}

SolverOptions solverOptionsFor(const Scene &scene, const RadiosityCommandOptions &o, MeshOptions &meshOptions) {
  SolverOptions solverOptions;
  solverOptions.solver = o.solver;
  applySolverParameters(o.parameters.given(), scene, solverOptions, meshOptions);
  if (solverOptions.importance) {
    // The view importance comes from: the scene's camera, as `render` has set it from --eye, --target, … .
    solverOptions.importanceView.camera = scene.camera;
    solverOptions.importanceView.aspect = double(scene.render.width) / std::max(1, scene.render.height);
  }
  return solverOptions;
}

SolverChoice chooseSolver(const Scene &scene, const RadiosityCommandOptions &o) {
  MeshOptions meshOptions;
  return chooseSolver(scene, solverOptionsFor(scene, o, meshOptions));
}

std::string whySolveAlone(const Scene &scene, const RadiosityCommandOptions &o) {
  if (o.solver != "auto" || !o.parameters.given().all().empty()) return {};
  const SolverChoice chosen = chooseSolver(scene, o);
  if (chosen.solver != "hierarchical-exact") return {};
  return fmt::format("auto's hierarchical-exact, for {}: a solve of seconds, which sharing would slow", chosen.reason);
}

Solution solveScene(const Scene &scene, const RayTracer &tracer, const RadiosityCommandOptions &o, uint64_t seed,
                    int threads, bool quiet, const SolveCheckpointOptions &checkpoint) {
  MeshOptions meshOptions;
  SolverOptions solverOptions = solverOptionsFor(scene, o, meshOptions);
  solverOptions.seed = seed;
  solverOptions.threads = threads;
  solverOptions.checkpoint = checkpoint;
  if (solverOptions.importance) {
    const SolverChoice chosen = chooseSolver(scene, solverOptions);
    if (chosen.solver != "hierarchical")
      throw InputError(InputLocation{"--importance"},
                       fmt::format("applies only to --solver hierarchical; --solver {} runs {} ({})", o.solver,
                                   chosen.solver, chosen.reason));
  }

  SolverProgressCallback progress;
  if (!quiet) {
    bool terminal = isatty(fileno(stderr));
    auto last = std::make_shared<std::chrono::steady_clock::time_point>(std::chrono::steady_clock::now());
    std::string name = o.solver;
    auto first = std::make_shared<SolverProgress>();
    progress = [terminal, last, first, name](const SolverProgress &p) {
      if (first->iteration == 0) *first = p;
      auto now = std::chrono::steady_clock::now();
      double since = std::chrono::duration<double>(now - *last).count();
      if (since < (terminal ? 0.2 : 5.0)) return;
      *last = now;
      // Residuals fall roughly geometrically: extrapolate log(residual) against time.
      std::string eta = "?";
      if (p.residual > 0 && first->residual > p.residual && p.elapsedSeconds > first->elapsedSeconds) {
        double rate = std::log(first->residual / p.residual) / (p.elapsedSeconds - first->elapsedSeconds);
        eta = fmt::format("{:.1f}s", std::max(0.0, std::log(p.residual / p.tolerance) / rate));
      }
      fmt::print(stderr, "{}{}: iteration {}, residual {:.3g} (target {:.3g}), {:.1f}s, ETA {}{}", terminal ? "\r" : "",
                 name, p.iteration, p.residual, p.tolerance, p.elapsedSeconds, eta, terminal ? "   " : "\n");
    };
  }
  // Ctrl-C (util/interrupt.h): the solve stops at its next report and nothing of it is kept.
  SolverProgressCallback report = [progress](const SolverProgress &p) {
    if (interruptRequested()) throw Interrupted();
    if (progress) progress(p);
  };
  Solution solution = meshAndSolve(scene, tracer, meshOptions, solverOptions, report);
  if (!quiet) {
    if (isatty(fileno(stderr))) fmt::print(stderr, "\n");
    if (solution.stats.resumedFromIteration >= 0)
      fmt::print(stderr, "radiant: resumed from {} after iteration {}\n", checkpoint.path,
                 solution.stats.resumedFromIteration);
    printSolveSummary(solution);
  }
  return solution;
}

Solution solvePreview(const Scene &scene, const RayTracer &tracer, const RadiosityCommandOptions &options, int shots,
                      uint64_t seed, int threads) {
  // The preview is always progressive: the given parameters it takes apply
  // (the mesh's among them), the rest are for the solution the later passes read.
  ParameterValues meshing;
  const ParameterTable &progressive = solverParameters("progressive");
  const ParameterValues given = options.parameters.given();
  for (const auto &[name, value] : given.all()) {
    const std::string &key = name;  // clang 14 (the sanitizer build) captures no structured binding
    if (key != "max-iterations" &&
        std::any_of(progressive.begin(), progressive.end(), [&](const ParameterSpec &s) { return s.name == key; }))
      meshing.set(key, value.text, value.origin);
  }
  MeshOptions meshOptions;
  SolverOptions solverOptions;
  solverOptions.solver = "progressive";
  applySolverParameters(meshing, scene, solverOptions, meshOptions);
  solverOptions.maxIterations = shots;
  solverOptions.seed = seed;
  solverOptions.threads = threads;
  return meshAndSolve(scene, tracer, meshOptions, solverOptions);
}

void printSolveSummary(const Solution &s) {
  const SolveStats &st = s.stats;
  fmt::print(stderr,
             "radiant: {} solved {} elements in {:.2f} s: {} iterations, residual {:.3g}, {:.3g} M shadow rays\n",
             st.solver, s.elementCount(), st.seconds, st.iterations, st.residual, st.formFactorRays * 1e-6);
  if (st.links > 0)
    fmt::print(stderr, "radiant: {} links, {} of them with a cluster of patches at an end\n", st.links,
               st.clusterLinks);
  fmt::print(stderr, "radiant: power (W, band average): emitted {:.6g}, absorbed {:.6g}, escaped {:.6g}",
             st.emittedPower.average(), st.absorbedPower.average(), st.escapedPower.average());
  if (st.escapedToBackSides.average() > 0)
    fmt::print(stderr, " ({:.3g} of it onto one-sided faces' backs)", st.escapedToBackSides.average());
  if (st.unshotPower.average() > 0) fmt::print(stderr, ", unshot {:.6g}", st.unshotPower.average());
  fmt::print(stderr, "; imbalance {:.3g}", st.powerImbalance());
  if (st.powerBalanceTolerance > 0) fmt::print(stderr, " (tolerance {:.2g})", st.powerBalanceTolerance);
  fmt::print(stderr, "\n");
  // The escaped power is measured by rays (radiosity/power_balance.h), not
  // inferred: an imbalance beyond what the solver's own error allows is a bug.
  if (std::abs(st.powerImbalance()) > st.powerBalanceTolerance && st.powerBalanceTolerance > 0)
    fmt::print(stderr,
               "radiant: warning: the {} solution does not balance: emitted {:.6g} W, absorbed {:.6g} W, escaped "
               "{:.6g} W, unshot {:.6g} W leave {:+.4g} W, beyond its tolerance of {:.3g} W; please report this "
               "scene\n",
               st.solver, st.emittedPower.average(), st.absorbedPower.average(), st.escapedPower.average(),
               st.unshotPower.average(), st.powerImbalance(), st.powerBalanceTolerance);
}

}  // namespace radiant
