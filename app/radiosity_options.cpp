#include "radiosity_options.h"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "mesh/mesh.h"
#include "radiosity/solver.h"
#include "util/error.h"

namespace radiant {

void addRadiosityOptions(CLI::App &app, RadiosityCommandOptions &o) {
  std::string solvers = fmt::format("\n  {:<13} {}", "auto",
                                    "hierarchical-exact up to 150 000 input faces (256 emitting), else stochastic");
  for (const SolverInfo &info : solverRegistry()) solvers += fmt::format("\n  {:<13} {}", info.name, info.summary);
  app.add_option("--solver", o.solver.solver, "Radiosity solver:" + solvers)->default_val("auto");
  app.add_option("--mesh-size", o.meshSize,
                 "Target element edge length in scene units (default: 1/8 of the scene's largest extent)")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-elements", o.solver.maxElements,
                 "Refuse uniform meshes with more elements than this; hierarchical stops refining there")
      ->default_val(2'000'000)
      ->check(CLI::Range(size_t(1), size_t(100'000'000)));
  app.add_option(
         "--tolerance", o.solver.tolerance,
         "Convergence in (0, 1]: unshot power over emitted power (progressive, stochastic), or the largest change "
         "of B in a sweep over the largest reflected radiosity (gauss-seidel, hierarchical)")
      ->default_val(1e-3)
      ->check(CLI::Validator(
          [](std::string &text) {
            double value = std::strtod(text.c_str(), nullptr);
            return value > 0 && value <= 1 ? std::string() : "must be in (0, 1], got " + text;
          },
          "in (0, 1]"));
  app.add_option("--max-iterations", o.solver.maxIterations, "Stop after this many shots or sweeps (0: no limit)")
      ->default_val(0)
      ->check(CLI::NonNegativeNumber);
  app.add_option("--ff-samples", o.solver.visibilitySamples,
                 "Shadow rays per form factor, rounded to a square number k x k (stratified)")
      ->default_val(4)
      ->check(CLI::Range(1, 1024));
  app.add_option("--form-factor", o.solver.formFactor,
                 "Progressive solver's form factors: analytic (contour integral x visible fraction), ray-cast "
                 "(Wallace 1989 disc sum), hemicube (Cohen & Greenberg 1985)")
      ->default_val("analytic")
      ->check(CLI::IsMember({"analytic", "ray-cast", "hemicube"}));
  app.add_option("--hemicube-resolution", o.solver.hemicubeResolution, "Hemicube pixels across the top face")
      ->default_val(64)
      ->check(CLI::Range(4, 4096));
  app.add_option("--link-threshold", o.solver.linkThreshold,
                 "Hierarchical: link when F*B_source is below this fraction of the largest emitted radiosity")
      ->default_val(1e-4)
      ->check(CLI::Range(0.0, 1.0));
  app.add_flag("--importance", o.solver.importance,
               "Hierarchical: refine for the scene's camera only (render: the camera it renders from); importance "
               "from the eye weighs each link (Smits, Arvo & Salesin 1992)");
  app.add_option("--adaptive-rounds", o.solver.adaptiveRounds,
                 "Gauss-Seidel, progressive, stochastic: rounds of splitting the elements whose error estimate "
                 "exceeds --adaptive-threshold and solving again (0: uniform mesh)")
      ->default_val(0)
      ->check(CLI::Range(0, 20));
  app.add_option("--adaptive-threshold", o.solver.adaptiveThreshold,
                 "Split elements whose nodes differ from them by more than this fraction of their radiosity")
      ->default_val(0.1)
      ->check(CLI::Range(0.0, 100.0));
  std::string levels;
  for (const QualityLevel &level : qualityLevels()) levels += fmt::format("\n  {:<13} {}", level.name, level.summary);
  app.add_option("--quality", o.quality, "hierarchical-exact (the default solver): accuracy against time:" + levels)
      ->default_val("high");
  app.add_option("--rays-per-element", o.solver.raysPerElement,
                 "Stochastic: rays of the first iteration per element (noise falls as 1/sqrt)")
      ->default_val(64)
      ->check(CLI::Range(1, 100000));
}

void rejectUnusedRadiosityOptions(const CLI::App &app, bool solving, const std::string &reason,
                                  const RadiosityCommandOptions &options) {
  const char *all[] = {"--solver",         "--mesh-size",        "--max-elements",    "--tolerance",
                       "--max-iterations", "--ff-samples",       "--form-factor",     "--hemicube-resolution",
                       "--link-threshold", "--rays-per-element", "--adaptive-rounds", "--adaptive-threshold",
                       "--importance",     "--quality"};
  for (const char *name : all) {
    if (app.get_option(name)->count() == 0) continue;
    if (!solving) throw InputError(InputLocation{name}, "has no effect here: " + reason);
    std::string flag = name;
    // "auto" may pick hierarchical or stochastic, so their options stay valid with it.
    auto only = [&](const char *solver, bool autoMayPickIt) {
      if (options.solver.solver != solver && !(autoMayPickIt && options.solver.solver == "auto"))
        throw InputError(InputLocation{name}, std::string("applies only to --solver ") + solver);
    };
    if (flag == "--form-factor" || flag == "--hemicube-resolution") only("progressive", false);
    if (flag == "--link-threshold") only("hierarchical", false);
    if (flag == "--importance") only("hierarchical", true);
    if (flag == "--rays-per-element") only("stochastic", true);
    if (flag == "--quality") only("hierarchical-exact", true);
    if (flag == "--ff-samples" && (options.solver.solver == "auto" || options.solver.solver == "hierarchical-exact" ||
                                   options.solver.solver == "stochastic"))
      throw InputError(InputLocation{name},
                       "applies only to --solver gauss-seidel, progressive or hierarchical "
                       "(hierarchical-exact computes visibility exactly, stochastic by its rays)");
    if ((flag == "--adaptive-rounds" || flag == "--adaptive-threshold") && options.solver.solver == "hierarchical")
      throw InputError(InputLocation{name},
                       "the hierarchical solver refines by itself; use --solver gauss-seidel, "
                       "progressive or stochastic");
    if (flag == "--adaptive-threshold" && app.get_option("--adaptive-rounds")->count() == 0)
      throw InputError(InputLocation{name}, "needs --adaptive-rounds");
  }
}

Solution solveScene(const Scene &scene, const RayTracer &tracer, const RadiosityCommandOptions &o, uint64_t seed,
                    int threads, bool quiet) {
  MeshOptions meshOptions;
  if (o.meshSize) meshOptions.maxEdgeLength = *o.meshSize * scene.metresPerUnit;
  meshOptions.maxElements = o.solver.maxElements;
  SolverOptions solverOptions = o.solver;
  applyQuality(solverOptions, o.quality);
  solverOptions.seed = seed;
  solverOptions.threads = threads;
  if (o.solver.importance) {
    // "auto" is settled by the patch count, one patch per face.
    const std::string resolved = resolveSolverName(o.solver.solver, scene.faces.size(), true);
    if (resolved != "hierarchical")
      throw InputError(InputLocation{"--importance"},
                       fmt::format("applies only to --solver hierarchical; --solver {} runs {} on {} patches",
                                   o.solver.solver, resolved, scene.faces.size()));
    // The view importance comes from: the scene's camera, as `render` has set it from --eye, --target, … .
    solverOptions.importanceView.camera = scene.camera;
    solverOptions.importanceView.aspect = double(scene.render.width) / std::max(1, scene.render.height);
  }

  SolverProgressCallback progress;
  if (!quiet) {
    bool terminal = isatty(fileno(stderr));
    auto last = std::make_shared<std::chrono::steady_clock::time_point>(std::chrono::steady_clock::now());
    std::string name = o.solver.solver;
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
  Solution solution = meshAndSolve(scene, tracer, meshOptions, solverOptions, progress);
  if (!quiet) {
    if (isatty(fileno(stderr))) fmt::print(stderr, "\n");
    printSolveSummary(solution);
  }
  return solution;
}

void printSolveSummary(const Solution &s) {
  const SolveStats &st = s.stats;
  fmt::print(stderr,
             "radiant: {} solved {} elements in {:.2f} s: {} iterations, residual {:.3g}, {:.3g} M shadow rays\n",
             st.solver, s.elementCount(), st.seconds, st.iterations, st.residual, st.formFactorRays * 1e-6);
  if (st.links > 0)
    fmt::print(stderr, "radiant: {} links, {} of them with a cluster of patches at an end\n", st.links,
               st.clusterLinks);
  fmt::print(stderr, "radiant: power (W, band average): emitted {:.6g}, absorbed {:.6g}, escaped {:.6g}\n",
             st.emittedPower.average(), st.absorbedPower.average(), st.escapedPower.average());
}

}  // namespace radiant
