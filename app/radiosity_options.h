// Options shared by `radiant solve` and the radiosity methods of `radiant render`.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "radiosity/solution.h"
#include "raytrace/ray_tracer.h"

namespace radiant {

struct RadiosityCommandOptions {
  std::string solver = "auto";
  std::optional<double> meshSize;  ///< scene units
  size_t maxElements = 2'000'000;
  double tolerance = 1e-3;
  int maxIterations = 0;
  int formFactorSamples = 4;
  std::string formFactor = "analytic";
  int hemicubeResolution = 64;
  double linkThreshold = 1e-4;
  int raysPerElement = 64;
  int adaptiveRounds = 0;
  double adaptiveThreshold = 0.1;
};

void addRadiosityOptions(CLI::App &app, RadiosityCommandOptions &options);

/// An option nothing will use is an error, not a silent no-op (STYLE.md §5):
/// radiosity options when no solution is computed (`reason` says why), and
/// progressive-only options with another solver.
void rejectUnusedRadiosityOptions(const CLI::App &app, bool solving, const std::string &reason,
                                  const RadiosityCommandOptions &options);

/// Meshes and solves the scene, printing progress and a summary unless quiet.
Solution solveScene(const Scene &scene, const RayTracer &tracer, const RadiosityCommandOptions &options,
                    uint64_t seed, int threads, bool quiet);

/// The solution's figures, for a person: solver, iterations, residual, energy balance.
void printSolveSummary(const Solution &solution);

}  // namespace radiant
