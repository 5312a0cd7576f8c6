// The solvers' parameter tables (util/parameters.h): which solver reads which
// of SolverOptions' fields, and the meshing parameters every solver takes.
// The defaults are SolverOptions' and MeshOptions' own, printed here, so they
// are written once.
#include <fmt/format.h>

#include "radiosity/solver.h"
#include "util/error.h"

namespace radiant {

namespace {

std::string text(double value) {
  return fmt::format("{}", value);
}

ParameterSpec meshSize() {
  return {"mesh-size",
          ParameterType::Real,
          "",
          "target element edge length, in scene units (mm for the Cornell box). hierarchical-exact: the starting "
          "mesh, refined from there; hierarchical: the size of its smallest elements (about 0.7–1.4 × this on a "
          "side), larger where less detail is needed",
          kPositive,
          std::numeric_limits<double>::infinity(),
          {},
          "1/8 of the scene's largest extent (stochastic with the direct light at the nodes: 1/32)"};
}

ParameterSpec maxElements() {
  return {"max-elements",
          ParameterType::Integer,
          text(double(MeshOptions{}.maxElements)),
          "refuse uniform meshes with more elements than this; hierarchical solvers stop refining there",
          1,
          1e8};
}

ParameterSpec tolerance() {
  return {"tolerance",
          ParameterType::Real,
          text(SolverOptions{}.tolerance),
          "convergence: unshot power over emitted power (progressive, stochastic), or the largest change of B in a "
          "sweep over the largest reflected radiosity (gauss-seidel, hierarchical solvers)",
          kPositive,
          1};
}

ParameterSpec maxIterations() {
  return {"max-iterations",
          ParameterType::Integer,
          text(SolverOptions{}.maxIterations),
          "stop after this many shots (progressive), sweeps (gauss-seidel; hierarchical solvers: per refinement "
          "round) or iterations (stochastic) even if the tolerance is not met; 0: the tolerance decides",
          0,
          2147483647};
}

ParameterSpec ffSamples() {
  return {"ff-samples",
          ParameterType::Integer,
          text(SolverOptions{}.visibilitySamples),
          "shadow rays per form factor: analytic uses a k × k grid, k = round(√S), so give a square number; ray-cast "
          "S pieces; hierarchical one ray from each point of an m × m grid on the receiver, m = max(4, round(√S))",
          1,
          1024};
}

ParameterSpec adaptiveRounds() {
  return {"adaptive-rounds",
          ParameterType::Integer,
          text(SolverOptions{}.adaptiveRounds),
          "rounds of splitting the elements whose error estimate exceeds adaptive-threshold and solving again "
          "(0: uniform mesh; Cohen et al. 1986)",
          0,
          20};
}

ParameterSpec adaptiveThreshold() {
  return {"adaptive-threshold",
          ParameterType::Real,
          text(SolverOptions{}.adaptiveThreshold),
          "with adaptive-rounds: split elements whose nodes differ from them by more than this fraction of their "
          "radiosity",
          0,
          100};
}

ParameterSpec importance() {
  return {"importance", ParameterType::Flag, "false",
          "refine for one view (Smits, Arvo & Salesin 1992): importance emitted by the camera (solve: the scene's; "
          "render: the one it renders from) is carried back over the links and weighs each, so what the view shows, "
          "and what lights it, is refined and the rest stays coarse. With auto, it picks hierarchical"};
}

ParameterSpec quality() {
  ParameterSpec spec{"quality", ParameterType::Choice, "high", "accuracy against time:"};
  for (const QualityLevel &level : qualityLevels()) {
    spec.choices.push_back(level.name);
    spec.documentation += fmt::format(" {} ({});", level.name, level.summary);
  }
  spec.documentation.pop_back();
  return spec;
}

ParameterSpec raysPerElement() {
  return {"rays-per-element",
          ParameterType::Integer,
          text(SolverOptions{}.raysPerElement),
          "rays of the first iteration per element (noise falls as 1/√rays)",
          1,
          100000};
}

ParameterSpec directLight() {
  ParameterSpec spec{
      "direct", ParameterType::Choice, "auto",
      "the light straight from the emitters: nodes (exact at every mesh node by backprojection, no noise; the rays "
      "carry the reflected light only, smoothed where the elements are too small for their rays), rays (shot with "
      "the first iteration's rays like the rest, per element: Neumann et al. 1994), or auto (nodes for up to 256 "
      "emitting faces, whose cost it multiplies)"};
  spec.choices = {"auto", "nodes", "rays"};
  return spec;
}

ParameterSpec hemicubeResolution() {
  return {"hemicube-resolution",
          ParameterType::Integer,
          text(SolverOptions{}.hemicubeResolution),
          "pixels across the hemicube's top face",
          4,
          4096};
}

ParameterSpec formFactor() {
  ParameterSpec spec{"form-factor", ParameterType::Choice, SolverOptions{}.formFactor,
                     "how the form factors are estimated:"};
  for (const FormFactorEstimatorInfo &e : formFactorEstimators()) {
    spec.choices.push_back(e.name);
    spec.documentation += fmt::format(" {} ({});", e.name, e.summary);
  }
  spec.documentation.pop_back();
  return spec;
}

ParameterTable withCommon(std::initializer_list<ParameterSpec> own) {
  ParameterTable table = {meshSize(), maxElements(), tolerance(), maxIterations()};
  table.insert(table.end(), own.begin(), own.end());
  return table;
}

}  // namespace

const std::vector<FormFactorEstimatorInfo> &formFactorEstimators() {
  static const std::vector<FormFactorEstimatorInfo> table = {
      {"analytic",
       "Lambert's contour integral × the visible fraction of the shooter, ff-samples shadow rays",
       {ffSamples()}},
      {"ray-cast", "Wallace et al. 1989: the shooter as ff-samples discs, one shadow ray each", {ffSamples()}},
      {"hemicube",
       "Cohen & Greenberg 1985: one hemicube at the shooter's centre, F_ji = F_ij A_i/A_j",
       {hemicubeResolution()}},
  };
  return table;
}

const ParameterTable &solverParameters(const std::string &name) {
  static const std::vector<std::pair<std::string, ParameterTable>> tables = {
      {"gauss-seidel", withCommon({ffSamples(), adaptiveRounds(), adaptiveThreshold()})},
      {"progressive",
       withCommon({formFactor(), ffSamples(), hemicubeResolution(), adaptiveRounds(), adaptiveThreshold()})},
      {"hierarchical",
       withCommon(
           {ffSamples(),
            {"link-threshold", ParameterType::Real, text(SolverOptions{}.linkThreshold),
             "link when F·B_source is below this fraction of the largest emitted radiosity (BF refinement)", 0, 1},
            importance()})},
      {"stochastic", withCommon({raysPerElement(), directLight(), adaptiveRounds(), adaptiveThreshold()})},
      {"hierarchical-exact", withCommon({quality()})},
      // What "auto" may pick (resolveSolverName): hierarchical-exact or
      // stochastic, and hierarchical when asked for importance.
      {"auto",
       withCommon({quality(), raysPerElement(), directLight(), adaptiveRounds(), adaptiveThreshold(), importance()})},
  };
  std::string names;
  for (const auto &[solver, table] : tables) {
    if (solver == name) return table;
    names += (names.empty() ? "" : ", ") + solver;
  }
  throw InputError(InputLocation::ofParameter("solver"), fmt::format("unknown solver '{}'; known: {}", name, names));
}

void checkSolverParameters(const std::string &solver, const ParameterValues &given) {
  std::vector<std::pair<std::string, const ParameterTable *>> others;
  for (const char *name : {"auto", "gauss-seidel", "progressive", "hierarchical", "stochastic", "hierarchical-exact"})
    others.push_back({name, &solverParameters(name)});
  checkParameters(solverParameters(solver), given, "solver " + solver, others);
}

void applySolverParameters(const ParameterValues &given, const Scene &scene, SolverOptions &options,
                           MeshOptions &mesh) {
  checkSolverParameters(options.solver, given);
  const ParameterTable &table = solverParameters(options.solver);
  const Parameters p(table, given);
  auto has = [&](const char *name) {
    for (const ParameterSpec &spec : table)
      if (spec.name == name) return true;
    return false;
  };
  if (p.given("mesh-size")) mesh.maxEdgeLength = p.real("mesh-size") * scene.metresPerUnit;
  mesh.maxElements = size_t(p.integer("max-elements"));
  options.maxElements = mesh.maxElements;
  options.tolerance = p.real("tolerance");
  options.maxIterations = int(p.integer("max-iterations"));
  if (has("ff-samples")) options.visibilitySamples = int(p.integer("ff-samples"));
  if (has("form-factor")) {
    options.formFactor = p.choice("form-factor");
    // The estimators' own parameters, checked against the chosen one's table.
    ParameterValues estimatorValues;
    std::vector<std::pair<std::string, const ParameterTable *>> estimators;
    const FormFactorEstimatorInfo *chosen = nullptr;
    for (const FormFactorEstimatorInfo &e : formFactorEstimators()) {
      estimators.push_back({e.name, &e.parameters});
      if (e.name == options.formFactor) chosen = &e;
      for (const ParameterSpec &spec : e.parameters)
        if (p.given(spec.name)) estimatorValues.set(spec.name, p.text(spec.name), p.origin(spec.name));
    }
    checkParameters(chosen->parameters, estimatorValues, "form-factor estimator " + options.formFactor, estimators);
  }
  if (has("hemicube-resolution")) options.hemicubeResolution = int(p.integer("hemicube-resolution"));
  if (has("link-threshold")) options.linkThreshold = p.real("link-threshold");
  if (has("importance")) options.importance = p.flag("importance");
  if (has("rays-per-element")) options.raysPerElement = int(p.integer("rays-per-element"));
  if (has("direct")) {
    const std::string direct = p.choice("direct");
    options.stochasticDirect = direct == "nodes"  ? SolverOptions::StochasticDirect::Nodes
                               : direct == "rays" ? SolverOptions::StochasticDirect::Rays
                                                  : SolverOptions::StochasticDirect::Auto;
  }
  if (has("adaptive-rounds")) {
    if (p.given("adaptive-threshold") && !p.given("adaptive-rounds"))
      throw InputError(p.origin("adaptive-threshold"), "needs adaptive-rounds");
    options.adaptiveRounds = int(p.integer("adaptive-rounds"));
    options.adaptiveThreshold = p.real("adaptive-threshold");
  }
  if (has("quality")) applyQuality(options, p.choice("quality"));
}

}  // namespace radiant
