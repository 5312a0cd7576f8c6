#include "radiosity/solver.h"

#include <fmt/format.h>

#include <chrono>

#include "radiosity/direct_light_mesh.h"
#include "radiosity/power_balance.h"
#include "scene/overlapping_faces.h"
#include "util/error.h"
#include "util/sampling.h"
#include "util/timing.h"

namespace radiant {

const std::vector<SolverInfo> &solverRegistry() {
  static const std::vector<SolverInfo> table = {
      {"gauss-seidel", "gathering on the full element form-factor matrix to a residual tolerance", &solveGaussSeidel},
      {"progressive", "progressive refinement shooting, with the ambient term and the direct/indirect split",
       &solveProgressive},
      {"hierarchical", "Hanrahan-Salzman-Aupperle hierarchical radiosity with BF refinement and push-pull",
       &solveHierarchical},
      {"stochastic", "stochastic Jacobi radiosity: shoots unshot power with rays, no form factors; for large scenes",
       &solveStochasticJacobi},
      {"hierarchical-exact",
       "direct light exact at every node (backprojection, mesh refined to the shadows); reflected light by "
       "hierarchical radiosity with an error-bounding oracle",
       &solveHierarchicalExact},
  };
  return table;
}

const std::vector<QualityLevel> &qualityLevels() {
  // Cornell box, 256², 2 threads (bench/radiosity_accuracy; docs/radiosity.md):
  // solve time and the interpolated image's RMSE against a converged path tracer.
  static const std::vector<QualityLevel> table = {
      {"draft", 0.01, 0.02, "about 0.25 s on the Cornell box, RMSE 0.0017"},
      {"low", 0.004, 0.04, "about 0.35 s, RMSE 0.00097"},
      {"normal", 0.003, 0.01, "about 0.55 s, RMSE 0.00076"},
      {"high", 0.001, 0.005, "the default: about 1.3 s, RMSE 0.00038, every object within 0.5 %"},
      {"best", 0.0003, 0.003, "about 3.5 s, RMSE below 0.0006"},
  };
  return table;
}

void applyQuality(SolverOptions &options, const std::string &name) {
  std::string names;
  for (const QualityLevel &level : qualityLevels()) {
    if (name == level.name) {
      options.linkError = level.linkError;
      options.directTolerance = level.directTolerance;
      return;
    }
    names += names.empty() ? level.name : std::string(", ") + level.name;
  }
  throw InputError(InputLocation::ofParameter("quality"), fmt::format("unknown quality '{}'; known: {}", name, names));
}

namespace {

/// The faces of an emitting material (either side) and the front faces.
std::pair<size_t, size_t> countEmittersAndFaces(const Scene &scene) {
  size_t emitters = 0, faces = 0;
  for (const Face &f : scene.faces) emitters += scene.materials[f.material].isEmitter(), faces += !f.back;
  return {emitters, faces};
}

constexpr size_t kMostNodeEmitters = 256;

}  // namespace

SolverChoice chooseSolver(const Scene &scene, const SolverOptions &options) {
  if (options.solver != "auto") return {options.solver, "named by --solver"};
  // hierarchical (for --importance) links every pair of input patches
  // first, hopeless beyond a few thousand. hierarchical-exact is the most
  // accurate where the input is a few large faces (the Cornell box: 2 s,
  // RMSE 0.0004), but its links and shadow refinement multiply with the
  // faces of a tessellated model: on 2 cores, whole runs at 256², 960
  // faces of a sphere 3.3 s, the 3.7k-face Wuson 18 s (worse than the path
  // tracer given those 18 s), 9 800 faces 17 s, 10⁵ (cornell-knots) 47 s.
  // The stochastic solver, with the direct light exact at the nodes and the
  // reflected light gathered at a model's nodes (reflected_light_gather.h),
  // takes 1.3–1.5 s on the first three and 9.5 s on the last, at 0.3–0.5×
  // the path tracer's RMSE given the same time (docs/PERFORMANCE.md, "The
  // default on the scenes users bring"). So beyond 2000 faces it takes over.
  // Its exact direct light costs a backprojection per emitter face at every
  // node: a room lit by a few lamps, not a furnace of 3750 glowing quads (5
  // minutes), so a scene of more than 256 emitting faces goes to the
  // stochastic solver with the emission shot by rays.
  constexpr size_t kAutoHierarchicalPatches = 2000, kAutoExactPatches = 2000;
  const auto [emitters, patches] = countEmittersAndFaces(scene);
  if (options.importance) {
    if (patches <= kAutoHierarchicalPatches)
      return {"hierarchical", fmt::format("--importance refines for the view, and {} patches (at most {}) can all be "
                                          "linked",
                                          patches, kAutoHierarchicalPatches)};
    return {"stochastic", fmt::format("--importance needs hierarchical, which links every pair of patches: too many "
                                      "at {} (more than {})",
                                      patches, kAutoHierarchicalPatches)};
  }
  if (emitters > kMostNodeEmitters)
    return {"stochastic", fmt::format("{} emitting faces (more than {}): the exact direct light at every node would "
                                      "cost a backprojection of each",
                                      emitters, kMostNodeEmitters)};
  if (patches > kAutoExactPatches)
    return {"stochastic",
            fmt::format("{} faces (more than {}): hierarchical-exact would take minutes", patches, kAutoExactPatches)};
  return {"hierarchical-exact",
          fmt::format("{} face{} (at most {}) and {} emitting face{} (at most {})", patches, patches == 1 ? "" : "s",
                      kAutoExactPatches, emitters, emitters == 1 ? "" : "s", kMostNodeEmitters)};
}

bool directLightAtNodes(const SolverOptions &options, const Scene &scene) {
  switch (options.stochasticDirect) {
    case SolverOptions::StochasticDirect::Nodes:
      return true;
    case SolverOptions::StochasticDirect::Rays:
      return false;
    case SolverOptions::StochasticDirect::Auto:
      break;
  }
  return countEmittersAndFaces(scene).first <= kMostNodeEmitters;
}

Solution meshAndSolve(const Scene &scene, const RayTracer &tracer, const MeshOptions &meshOptions,
                      const SolverOptions &given, const SolverProgressCallback &progress) {
  // Every solve comes through here: a scene of no faces (an empty OBJ, one
  // of points or lines only) has nothing to mesh, and the solvers assume a mesh.
  if (scene.faces.empty())
    throw InputError(InputLocation{scene.sourceFile, 0, 0, ""}, "the scene has no faces: there is nothing to solve");
  // "auto" decided once, here, for the meshing and the solve alike.
  SolverOptions options = given;
  options.solver = chooseSolver(scene, given).solver;
  if (options.solver == "hierarchical-exact") {
    // It refines the patches' trees itself, from a uniform start.
    if (options.adaptiveRounds > 0)
      throw InputError(InputLocation::ofParameter("adaptive-rounds"), "hierarchical-exact refines by itself");
    // Faces cut where other surfaces meet them, hidden parts left out (mesh/face_split.h).
    TimingLaps cutting;
    const std::vector<FaceSplit> splits = splitFaces(scene, tracer);
    cutting.lap("cutting faces");
    MeshOptions cut = meshOptions;
    cut.faceSplits = &splits;
    Solution s = initialSolution(scene, buildTreeMesh(scene, cut));
    solveRadiosity(tracer, s, options, progress);
    return s;
  }
  if (options.adaptiveRounds <= 0) {
    // The large-scene solver meshes the cut faces too (no leaks, nothing hidden meshed).
    std::vector<FaceSplit> splits;
    MeshOptions uniform = meshOptions;
    bool followDirectLight = false;
    if (options.solver == "stochastic") {
      splits = splitFaces(scene, tracer);
      uniform.faceSplits = &splits;
      // With the direct light exact at the nodes, the display interpolates
      // it between them: the walls' elements must be small enough to follow
      // the light's falloff, which 1/8 of the scene is not (the
      // 10⁶-triangle sphere in a room: RMSE 0.0057 at 1/8, 0.0023 at 1/32;
      // docs/PERFORMANCE.md), and a model's contact shadow on the floor is
      // narrower still: the large surfaces start at 1/32 and are refined to
      // the direct light (direct_light_mesh.h). A large scene's elements are
      // its model's facets, so this adds little.
      if (directLightAtNodes(options, scene)) uniform.defaultEdgeFraction = 1.0 / 32, followDirectLight = true;
    }
    Solution s;
    if (followDirectLight) {
      DirectLightMesh refined = buildDirectLightMesh(scene, tracer, uniform, options);
      s = initialSolution(scene, std::move(refined.mesh));
      s.knownNodeDirect = std::move(refined.nodeDirect), s.knownElementDirect = std::move(refined.elementDirect);
    } else {
      s = initialSolution(scene, buildMesh(scene, uniform));
    }
    solveRadiosity(tracer, s, options, progress);
    return s;
  }
  if (!options.checkpoint.path.empty())
    throw InputError(InputLocation{"--checkpoint"}, "not with adaptive rounds (a solve per round)");
  RadiosityMesh mesh = buildTreeMesh(scene, meshOptions);
  const SolverOptions &round = options;
  if (round.solver == "hierarchical")
    throw InputError(InputLocation::ofParameter("adaptive-rounds"),
                     "the hierarchical solver refines by itself; adaptive rounds are for --solver gauss-seidel, "
                     "progressive or stochastic");
  Solution s = initialSolution(scene, mesh);
  solveRadiosity(tracer, s, round, progress);
  double seconds = s.stats.seconds;
  int iterations = s.stats.iterations;
  size_t rays = s.stats.formFactorRays;
  for (int r = 0; r < options.adaptiveRounds; ++r) {
    if (refineMesh(mesh, s.errorEstimate, options.adaptiveThreshold, options.maxElements) == 0) break;
    s = initialSolution(scene, mesh);
    solveRadiosity(tracer, s, round, progress);
    seconds += s.stats.seconds;
    iterations += s.stats.iterations;
    rays += s.stats.formFactorRays;
  }
  s.stats.seconds = seconds;  // all rounds together
  s.stats.iterations = iterations;
  s.stats.formFactorRays = rays;
  return s;
}

namespace {

/// What went wrong (the residual's growth, or more light absorbed than emitted) and the overlapping faces.
[[noreturn]] void divergenceError(const Scene &scene, const std::string &what) {
  const std::vector<FaceOverlap> overlaps = findOverlappingFaces(scene, 10000);
  throw InputError(
      InputLocation{scene.sourceFile, 0, 0, ""},
      fmt::format("{}; {}", what,
                  overlaps.empty() ? std::string("no overlapping faces were found; please report this scene")
                                   : describeOverlappingFaces(scene, overlaps) +
                                         ", and each is given all the light of the plane: keep one copy"));
}

/// The escaped power measured (power_balance.h), and the imbalance this solver may show.
void measureBalance(const RayTracer &tracer, Solution &solution, const SolverOptions &options) {
  const ScopedTiming timing("power balance");
  const PowerBalance balance = measurePowerBalance(tracer, solution, kPowerBalanceRays, options.seed);
  SolveStats &stats = solution.stats;
  stats.escapedPower = balance.escaped;
  stats.escapedToBackSides = balance.escapedToBackSides;
  stats.unshotPower = balance.unshot;
  stats.escapedStandardError = balance.escapedStandardError;
  stats.powerBalanceTolerance = powerBalanceTolerance(solution, options, balance);
}

}  // namespace

void solveRadiosity(const RayTracer &tracer, Solution &solution, const SolverOptions &options,
                    const SolverProgressCallback &progress) {
  const std::string name = chooseSolver(tracer.scene(), options).solver;
  const SolverInfo *chosen = nullptr;
  std::string names = "auto";
  for (const SolverInfo &info : solverRegistry()) {
    if (name == info.name) chosen = &info;
    names += std::string(", ") + info.name;
  }
  if (!chosen)
    throw InputError(InputLocation::ofParameter("solver"),
                     fmt::format("unknown solver '{}'; known solvers: {}", options.solver, names));
  if (!options.checkpoint.path.empty() && std::string(chosen->name) != "stochastic")
    throw InputError(InputLocation{"--checkpoint"},
                     fmt::format("only the stochastic solver saves its state yet; this solve runs {}", chosen->name));
  auto start = std::chrono::steady_clock::now();
  solution.stats.solver = chosen->name;
  // With every ρ < 1 and form factors that sum to at most 1, each iteration
  // leaves less light to distribute: a residual that grows tenfold means the
  // system is creating light, which happens where surfaces overlap in one
  // plane (each copy is given the whole light of the plane). Without this
  // guard the shooting solver runs on until its shot limit, diverging.
  const Scene &scene = tracer.scene();
  double firstResidual = -1;
  SolverProgressCallback guarded = [&](const SolverProgress &p) {
    if (firstResidual < 0) firstResidual = p.residual;
    if (p.residual > std::max(1.0, 10 * firstResidual))
      divergenceError(scene, fmt::format("the {} solution diverges: its residual grew to {:.3g} by iteration {}",
                                         chosen->name, p.residual, p.iteration));
    if (progress) progress(p);
  };
  chosen->solve(tracer, solution, options, guarded);
  // A converged solution of overlapping copies absorbs up to twice what is
  // emitted; Monte Carlo form factors stay within a few per cent.
  const double emitted = solution.stats.emittedPower.average(), absorbed = solution.stats.absorbedPower.average();
  if (emitted > 0 && absorbed > 1.05 * emitted)
    divergenceError(scene, fmt::format("the {} solution absorbs {:.4g} W of the {:.4g} W emitted, which no closed "
                                       "set of surfaces can",
                                       chosen->name, absorbed, emitted));
  solution.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  solution.updateNodesAndErrors();
  // After the node values: the tolerance reads H at the nodes.
  measureBalance(tracer, solution, options);
}

double visibleFraction(const RayTracer &tracer, const Vec3 &p, const Vec3 &n, const std::vector<Vec3> &polygon,
                       const Vec3 &polygonNormal, int samples, Pcg32 &rng) {
  // Stratified over the unit square: a k × k jittered grid, mapped onto the
  // quad bilinearly or onto the triangle by Heitz's map.
  int k = std::max(1, static_cast<int>(std::lround(std::sqrt(double(samples)))));
  int visible = 0, inFront = 0;
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b) {
      double u = (a + rng.next()) / k, v = (b + rng.next()) / k;
      Vec3 y;
      if (polygon.size() == 4) {
        y = polygon[0] * ((1 - u) * (1 - v)) + polygon[1] * (u * (1 - v)) + polygon[2] * (u * v) +
            polygon[3] * ((1 - u) * v);
      } else {
        double b1, b2;
        sampleUniformTriangle(u, v, b1, b2);
        y = polygon[0] * (1 - b1 - b2) + polygon[1] * b1 + polygon[2] * b2;
      }
      // The form factor this fraction multiplies covers only the part of the
      // polygon in front of p's tangent plane; a sample behind it would always
      // read as occluded and bias the fraction low.
      if (dot(y - p, n) <= 0) continue;
      ++inFront;
      if (tracer.visible(p, n, y, polygonNormal)) ++visible;
    }
  return inFront ? double(visible) / inFront : 0.0;
}

}  // namespace radiant
