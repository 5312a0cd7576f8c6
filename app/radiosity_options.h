// Options shared by `radiant solve` and the radiosity methods of `radiant render`.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "radiosity/solution.h"
#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"

namespace radiant {

/// The flags fill the solver's own options directly; only the mesh size,
/// given in scene units, waits for the scene to be converted.
struct RadiosityCommandOptions {
  SolverOptions solver;
  std::optional<double> meshSize;  ///< scene units
  std::string quality = "high";    ///< hierarchical-exact's preset (radiosity/solver.h qualityLevels)
};

void addRadiosityOptions(CLI::App &app, RadiosityCommandOptions &options);

/// An option nothing will use is an error, not a silent no-op (STYLE.md §5):
/// radiosity options when no solution is computed (`reason` says why), and
/// progressive-only options with another solver.
void rejectUnusedRadiosityOptions(const CLI::App &app, bool solving, const std::string &reason,
                                  const RadiosityCommandOptions &options);

/// Meshes and solves the scene, printing progress and a summary unless quiet.
Solution solveScene(const Scene &scene, const RayTracer &tracer, const RadiosityCommandOptions &options, uint64_t seed,
                    int threads, bool quiet);

/// The solution's figures, for a person: solver, iterations, residual, energy balance.
void printSolveSummary(const Solution &solution);

}  // namespace radiant
