// Options shared by `radiant solve` and the radiosity methods of `radiant render`.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "parameter_flags.h"
#include "radiosity/solution.h"
#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"

namespace radiant {

/// --solver and the solvers' parameters, whose flags come from their tables
/// (radiosity/solver.h solverParameters).
struct RadiosityCommandOptions {
  std::string solver = "auto";
  CLI::Option *solverOption = nullptr;
  ParameterFlags parameters;
};

void addRadiosityOptions(CLI::App &app, RadiosityCommandOptions &options);

/// An option nothing will use is an error, not a silent no-op:
/// a radiosity option when no solution is computed (`reason` says why), and a
/// solver's parameter given to another solver (checkSolverParameters).
void checkRadiosityOptions(const RadiosityCommandOptions &options, bool solving, const std::string &reason);

/// The solver options the flags ask for on this scene (mesh-size in its units, the importance view from its camera).
SolverOptions solverOptionsFor(const Scene &scene, const RadiosityCommandOptions &options, MeshOptions &meshOptions);
/// What the solve of these flags will run, and why (radiosity/solver.h chooseSolver).
SolverChoice chooseSolver(const Scene &scene, const RadiosityCommandOptions &options);

/// Why the solve of these flags under several MPI ranks is better run by rank
/// 0 alone, or empty when the ranks share it: `auto`'s hierarchical-exact with
/// no solver parameter given. Auto picks it only for a scene of a few
/// thousand faces whose solve takes seconds on one machine, and sharing such
/// a solve over 3 ranks tripled its wall time and doubled its CPU time (MPI's
/// start and the waits at every batch of links, docs/cluster.md). A solver
/// named, or given parameters (a finer mesh, a lower threshold), is shared.
std::string whySolveAlone(const Scene &scene, const RadiosityCommandOptions &options);

/// Meshes and solves the scene, printing progress and a summary unless quiet.
Solution solveScene(const Scene &scene, const RayTracer &tracer, const RadiosityCommandOptions &options, uint64_t seed,
                    int threads, bool quiet, const SolveCheckpointOptions &checkpoint = {});
/// A progressive solution interrupted after `shots` shots, on the mesh the
/// options' mesh-size and max-elements ask for (multipass's preview); quiet.
Solution solvePreview(const Scene &scene, const RayTracer &tracer, const RadiosityCommandOptions &options, int shots,
                      uint64_t seed, int threads);

/// The solution's figures, for a person: solver, iterations, residual, energy balance.
void printSolveSummary(const Solution &solution);

}  // namespace radiant
