// The stochastic solver's checkpoint (radiosity/stochastic_jacobi.cpp): after
// an iteration, every few seconds and when stopped, the per-element state it
// carries into the next one — radiosity, its direct and indirect parts, the
// unshot radiosity, the irradiance, the point lights' light still to shoot,
// the light through translucent faces, the rays each element received —
// and the iteration count. Each iteration draws its rays from generators
// seeded by (seed, chunk, iteration), so a solve resumed from the state after
// iteration k ends with the very solution of one never stopped.
//
// Binary, host byte order, written atomically (render/checkpoint.h's
// conventions); it records the job (the scene's and options' fingerprint)
// and is refused for another.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "util/spectrum.h"

namespace radiant {

/// Where and how often a solve saves its state (SolverOptions::checkpoint).
struct SolveCheckpointOptions {
  std::string path;  ///< empty: no checkpoints
  double intervalSeconds = 10;
  bool resume = false;  ///< carry on from `path` when it exists
  std::string job;      ///< fingerprint, written and required
  /// Save the finished solve's state too: a spectral pass's solution, which
  /// the passes after it must not lose to a kill (resumed, it ends at once).
  bool saveWhenDone = false;
};

struct StochasticCheckpoint {
  int iteration = 0;           ///< complete iterations
  bool emissionFirst = false;  ///< the emitters' light still goes before the point lights'
  uint64_t formFactorRays = 0;
  double seconds = 0;  ///< solve time before the checkpoint
  std::vector<Bands> radiosity, direct, indirect, unshot, irradiance;
  std::vector<Bands> lightGain;  ///< the point lights' reflected light not shot yet (may be empty)
  /// The light through translucent faces (Solution::transmittedDirect; empty when nothing is translucent).
  std::vector<Bands> transmittedDirect, transmittedIndirect;
  std::vector<double> raysArrived;  ///< per element: the rays that brought its reflected light
};

/// Writes it atomically (std::runtime_error naming the file on failure).
void writeStochasticCheckpoint(const std::string &path, const std::string &job, const StochasticCheckpoint &state);

/// Reads a checkpoint of `elements` elements written for `job`; InputError
/// naming the file for anything else.
StochasticCheckpoint readStochasticCheckpoint(const std::string &path, const std::string &job, size_t elements);

}  // namespace radiant
