// The stochastic solver's checkpoints (radiosity/solve_checkpoint.h): a
// solve stopped after any iteration and resumed from its checkpoint ends
// with the very solution of one never stopped; a checkpoint of another job or
// mesh, or a damaged one, is refused with the file named; the other solvers
// refuse to checkpoint.
#include "radiosity/solve_checkpoint.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "mesh/mesh.h"
#include "radiosity/solver.h"
#include "scene/load_scene.h"
#include "util/error.h"
#include "util/interrupt.h"

namespace radiant {
namespace {

struct TempFile {
  std::string path = (std::filesystem::temp_directory_path() /
                      ("radiant-solve-checkpoint-test-" + std::to_string(::getpid()) + ".bin"))
                         .string();
  ~TempFile() { std::filesystem::remove(path); }
};

SolverOptions stochastic(const std::string &checkpoint) {
  SolverOptions options;
  options.solver = "stochastic";
  options.raysPerElement = 16;
  options.threads = 2;
  options.checkpoint.path = checkpoint;
  options.checkpoint.intervalSeconds = 0;  // after every iteration
  options.checkpoint.resume = true;
  options.checkpoint.job = "solve checkpoint test";
  return options;
}

Solution solveCornellBox(const Scene &scene, const RayTracer &tracer, const SolverOptions &options,
                         const SolverProgressCallback &progress = {}) {
  MeshOptions mesh;
  mesh.maxEdgeLength = 0.08;
  return meshAndSolve(scene, tracer, mesh, options, progress);
}

TEST(SolveCheckpoint, AResumedStochasticSolveEqualsTheUninterruptedOne) {
  const Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  const RayTracer tracer(scene);
  const Solution whole = solveCornellBox(scene, tracer, stochastic(""));
  ASSERT_GT(whole.stats.iterations, 4);
  for (int stopAfter : {1, 2, whole.stats.iterations - 1}) {
    SCOPED_TRACE(stopAfter);
    TempFile checkpoint;
    // Stopped as Ctrl-C stops it: the progress report after iteration `stopAfter` throws.
    EXPECT_THROW(solveCornellBox(scene, tracer, stochastic(checkpoint.path),
                                 [&](const SolverProgress &p) {
                                   if (p.iteration == stopAfter) throw Interrupted();
                                 }),
                 Interrupted);
    const Solution resumed = solveCornellBox(scene, tracer, stochastic(checkpoint.path));
    EXPECT_EQ(resumed.stats.resumedFromIteration, stopAfter);
    EXPECT_EQ(resumed.stats.iterations, whole.stats.iterations);
    EXPECT_EQ(resumed.stats.formFactorRays, whole.stats.formFactorRays);
    ASSERT_EQ(resumed.elementCount(), whole.elementCount());
    size_t differing = 0;
    for (size_t e = 0; e < whole.elementCount(); ++e)
      for (int b = 0; b < kBandCount; ++b)
        differing += resumed.radiosity[e][b] != whole.radiosity[e][b] || resumed.direct[e][b] != whole.direct[e][b] ||
                     resumed.irradiance[e][b] != whole.irradiance[e][b];
    EXPECT_EQ(differing, 0u) << "element values differing between the resumed and the uninterrupted solve";
    // The display's node values too: the reflected light's density estimate
    // reads the rays each element received, which the checkpoint carries.
    ASSERT_EQ(resumed.nodeRadiosity.size(), whole.nodeRadiosity.size());
    size_t differingNodes = 0;
    for (size_t v = 0; v < whole.nodeRadiosity.size(); ++v)
      for (int b = 0; b < kBandCount; ++b) differingNodes += resumed.nodeRadiosity[v][b] != whole.nodeRadiosity[v][b];
    EXPECT_EQ(differingNodes, 0u) << "node values differing between the resumed and the uninterrupted solve";
  }
}

TEST(SolveCheckpoint, AnotherJobsOrADamagedCheckpointIsRefused) {
  TempFile checkpoint;
  StochasticCheckpoint state;
  state.iteration = 3;
  state.radiosity = state.direct = state.indirect = state.unshot = state.irradiance = std::vector<Bands>(10);
  state.raysArrived.assign(10, 0.0);
  writeStochasticCheckpoint(checkpoint.path, "job A", state);
  auto refusal = [&](const std::string &job, size_t elements) {
    try {
      readStochasticCheckpoint(checkpoint.path, job, elements);
    } catch (const InputError &e) {
      EXPECT_EQ(e.location().file, checkpoint.path);
      return e.message();
    }
    return std::string();
  };
  EXPECT_EQ(refusal("job A", 10), "");
  EXPECT_EQ(readStochasticCheckpoint(checkpoint.path, "job A", 10).iteration, 3);
  EXPECT_NE(refusal("job B", 10).find("another job"), std::string::npos);
  EXPECT_NE(refusal("job A", 11).find("10 elements"), std::string::npos);
  std::filesystem::resize_file(checkpoint.path, std::filesystem::file_size(checkpoint.path) - 8);
  EXPECT_NE(refusal("job A", 10).find("truncated"), std::string::npos);
  std::ofstream(checkpoint.path) << "# this is a scene description, not a checkpoint at all";
  EXPECT_NE(refusal("job A", 10).find("RADIANT-SOLVE-CHECKPOINT"), std::string::npos);
}

TEST(SolveCheckpoint, OnlyTheStochasticSolverCheckpoints) {
  const Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  const RayTracer tracer(scene);
  TempFile checkpoint;
  SolverOptions options = stochastic(checkpoint.path);
  options.solver = "gauss-seidel";
  try {
    solveCornellBox(scene, tracer, options);
    ADD_FAILURE() << "gauss-seidel accepted a checkpoint";
  } catch (const InputError &e) {
    EXPECT_NE(std::string(e.what()).find("only the stochastic solver"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace radiant
