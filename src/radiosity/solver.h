// Radiosity solvers: from a mesh and the scene to a Solution.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "radiosity/solution.h"
#include "radiosity/solve_checkpoint.h"
#include "raytrace/ray_tracer.h"
#include "scene/camera.h"
#include "util/parameters.h"
#include "util/random.h"

namespace radiant {

/// The view a view-dependent solve is for (SolverOptions::importance): the
/// camera as `radiant render` would use it and its image's shape.
struct ImportanceView {
  CameraSettings camera;
  double aspect = 1;     ///< image width / height
  int resolution = 128;  ///< rows of the internal image importance is traced at; columns = rows × aspect
};

struct SolverOptions {
  /// A name from solverRegistry(), or "auto" (chooseSolver decides).
  std::string solver = "auto";
  /// Gauss–Seidel and hierarchical: max change of B in a sweep over the
  /// largest reflected radiosity B − E; progressive: unshot power over
  /// emitted power.
  double tolerance = 1e-3;
  int maxIterations = 0;      ///< sweeps or shots; 0: no limit beyond the tolerance
  int visibilitySamples = 4;  ///< shadow rays per form factor
  /// Progressive: how F(dA_j → A_i) is estimated. "analytic": Lambert's contour
  /// integral × the visible fraction of the shooter; "ray-cast": Wallace et
  /// al.'s disc sum; "hemicube": one hemicube at the shooter, F_ji = F_ij A_i/A_j.
  std::string formFactor = "analytic";
  int hemicubeResolution = 64;
  /// Hierarchical: link when the radiosity a link would carry, F·B_source,
  /// is below this fraction of the largest emitted radiosity (BF refinement).
  double linkThreshold = 1e-4;
  /// Hierarchical: a node is split only while its area exceeds twice this,
  /// m² (0: the largest element of the uniform mesh), so leaves end at ½–2×.
  double minimumArea = 0;
  /// Stochastic: rays in the first iteration per element (later iterations
  /// shoot fewer, in proportion to the unshot power left).
  int raysPerElement = 64;
  /// Stochastic: the direct light exact at the mesh's nodes
  /// (radiosity/node_direct_light.h) and the rays for the reflected light
  /// only (Nodes), or shot by the first iteration's rays with the rest
  /// (Rays); Auto: Nodes for a scene of at most 256 emitting faces
  /// (directLightAtNodes).
  enum class StochasticDirect { Auto, Nodes, Rays };
  StochasticDirect stochasticDirect = StochasticDirect::Auto;
  int refinementRounds = 6;
  /// hierarchical-exact (radiosity/hierarchical_exact.cpp): tolerances relative to
  /// the scene's mean first-bounce radiosity (the area mean of ρ·H_direct).
  /// The direct light is refined until it interpolates within this fraction…
  double directTolerance = 0.005;
  /// …down to leaves of this edge, metres (0: 1/256 of the scene's extent);
  double directMinimumEdge = 0;
  /// a link is refined while its estimated error exceeds this fraction…
  double linkError = 0.001;
  /// …and its nodes' edges are at least twice this, metres (0: 1/64 of the extent).
  double linkMinimumEdge = 0;
  /// Hierarchical, --importance: refine for `importanceView` only (Smits,
  /// Arvo & Salesin 1992; radiosity/importance.h): links are judged by
  /// F·B_source times the importance of the receiver, which the camera emits
  /// and the links carry back, so what the view does not show stays coarse.
  bool importance = false;
  ImportanceView importanceView;
  /// Hierarchical: stop subdividing when the leaves would exceed this (--max-elements).
  size_t maxElements = 2'000'000;
  /// meshAndSolve with another solver: rounds of "split the elements whose
  /// error estimate exceeds adaptiveThreshold, solve again" (0: uniform mesh).
  int adaptiveRounds = 0;
  double adaptiveThreshold = 0.1;  ///< hierarchical: refine, solve, re-refine with the new B, … (at most)
  uint64_t seed = 1;
  int threads = 0;  ///< 0: all cores; results do not depend on it
  /// Stochastic: save the state after an iteration every so often, resume
  /// from it (radiosity/solve_checkpoint.h); the other solvers refuse it.
  SolveCheckpointOptions checkpoint;
};

struct SolverProgress {
  int iteration = 0;
  double residual = 0;  ///< as SolveStats::residual
  double tolerance = 0;
  double elapsedSeconds = 0;
};
using SolverProgressCallback = std::function<void(const SolverProgress &)>;

struct SolverInfo {
  const char *name;
  const char *summary;
  void (*solve)(const RayTracer &, Solution &, const SolverOptions &, const SolverProgressCallback &);
};

/// The table of solvers (radiosity/solver.cpp).
const std::vector<SolverInfo> &solverRegistry();

/// hierarchical-exact's accuracy presets (--quality): how far the links are
/// refined and how closely the mesh follows the direct light, chosen by
/// measurement on the Cornell box (docs/radiosity.md, "Choosing --quality").
struct QualityLevel {
  const char *name;
  double linkError, directTolerance;
  const char *summary;
};
const std::vector<QualityLevel> &qualityLevels();
/// Sets options.linkError and options.directTolerance from the named preset;
/// throws InputError (naming --quality) for an unknown name.
void applyQuality(SolverOptions &options, const std::string &name);

/// A solver's parameters (util/parameters.h), "auto" included: its table
/// holds what auto may pick. The meshing parameters (mesh-size, max-elements)
/// and tolerance and max-iterations are every solver's. Throws InputError
/// (the parameter "solver") for an unknown name.
const ParameterTable &solverParameters(const std::string &solver);
/// The progressive solver's form-factor estimators (its form-factor
/// parameter), each with the parameters it reads: a parameter of another
/// estimator is refused like a parameter of another solver.
struct FormFactorEstimatorInfo {
  const char *name;
  const char *summary;
  ParameterTable parameters;
};
const std::vector<FormFactorEstimatorInfo> &formFactorEstimators();

/// Checks `given` against the solver's table before any work (util/parameters.h).
void checkSolverParameters(const std::string &solver, const ParameterValues &given);
/// Checks `given` against options.solver's table (util/parameters.h
/// checkParameters: an error names the solvers that use a misplaced one) and
/// sets the fields of `options` and `mesh` it names, the others to their
/// defaults; mesh-size is in scene units.
void applySolverParameters(const ParameterValues &given, const Scene &scene, SolverOptions &options, MeshOptions &mesh);

/// Builds nothing: solves in place on an initialSolution(). Throws InputError
/// for an unknown solver name. Fills stats (energy balance, time) and the
/// nodal values and error estimates.
void solveRadiosity(const RayTracer &tracer, Solution &solution, const SolverOptions &options,
                    const SolverProgressCallback &progress = {});

/// Whether the stochastic solver computes the direct light at the nodes:
/// options.stochasticDirect, Auto being Nodes up to 256 emitting faces (the
/// exact light costs a backprojection per emitter at every node: a furnace
/// of 3750 glowing quads would take minutes) and Rays beyond.
bool directLightAtNodes(const SolverOptions &options, const Scene &scene);

/// What a solve runs: "auto" resolved (here and nowhere else), or the solver
/// named, with the reason for a person (radiant info, the solve's summary).
struct SolverChoice {
  std::string solver;  ///< a name from solverRegistry() (an unknown name is passed through for the caller to refuse)
  std::string reason;  ///< why auto picked it; for a named solver, "named by --solver"
};
/// What "auto" picks, in a line (the --solver help, `radiant methods`).
constexpr const char *kAutoSolverSummary = "hierarchical-exact up to 2000 input faces (256 emitting), else stochastic";
/// The one place "auto" is decided, from the scene's front faces (the
/// patches), its emitting faces and options.solver and options.importance
/// (docs/radiosity.md, "What auto chooses"). Every caller that needs to know
/// the solver before the solve (the app's checks, checkpoints, info) asks this.
SolverChoice chooseSolver(const Scene &scene, const SolverOptions &options);

/// Meshes the scene and solves it. With options.adaptiveRounds > 0 the mesh is
/// a tree mesh, and each round splits the elements whose error estimate
/// (Solution::errorEstimate) exceeds options.adaptiveThreshold, worst first
/// within options.maxElements, and solves again (Cohen et al. 1986's adaptive
/// subdivision). The hierarchical solver refines by itself and refuses rounds.
Solution meshAndSolve(const Scene &scene, const RayTracer &tracer, const MeshOptions &meshOptions,
                      const SolverOptions &options, const SolverProgressCallback &progress = {});

/// Fraction of `samples` stratified points on `polygon` (front normal
/// `polygonNormal`) visible from p (normal n), among those in front of p's
/// tangent plane (the part a clipped form factor covers). Deterministic for `rng`.
double visibleFraction(const RayTracer &tracer, const Vec3 &p, const Vec3 &n, const std::vector<Vec3> &polygon,
                       const Vec3 &polygonNormal, int samples, Pcg32 &rng);

// The solvers, one file each.
void solveGaussSeidel(const RayTracer &, Solution &, const SolverOptions &, const SolverProgressCallback &);
void solveProgressive(const RayTracer &, Solution &, const SolverOptions &, const SolverProgressCallback &);
void solveHierarchical(const RayTracer &, Solution &, const SolverOptions &, const SolverProgressCallback &);
void solveStochasticJacobi(const RayTracer &, Solution &, const SolverOptions &, const SolverProgressCallback &);
void solveHierarchicalExact(const RayTracer &, Solution &, const SolverOptions &, const SolverProgressCallback &);

}  // namespace radiant
