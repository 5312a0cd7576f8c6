// radiant solve SCENE — meshes the scene, computes its radiosity solution,
// reports it, and optionally saves it for `radiant render --solution`.
#include <fmt/format.h>

#include <cctype>
#include <filesystem>
#include <optional>

#include "checkpoint_options.h"
#include "cluster/cluster.h"
#include "colour_options.h"
#include "commands.h"
#include "display/grid_plan.h"
#include "interrupt_handler.h"
#include "io/image.h"
#include "io/output_files.h"
#include "io/solution_file.h"
#include "parameter_flags.h"
#include "phase_console.h"
#include "radiosity/calculation_grid.h"
#include "radiosity/report.h"
#include "radiosity_options.h"
#include "scene/load_scene.h"
#include "scene/spectral_scene.h"
#include "util/file_extension.h"
#include "util/interrupt.h"

namespace radiant {

namespace {
/// The plan of each grid: PATH itself for a scene with one grid, else
/// PATH's stem, "-", the grid's name (characters other than letters, digits,
/// '-' and '_' as '_') and the extension.
std::vector<std::string> gridImagePaths(const std::string &path, const std::vector<CalculationGrid> &grids) {
  if (grids.size() == 1) return {path};
  const std::filesystem::path p(path);
  std::vector<std::string> paths;
  for (const CalculationGrid &g : grids) {
    std::string name = g.name;
    for (char &ch : name)
      if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_') ch = '_';
    paths.push_back((p.parent_path() / (p.stem().string() + "-" + name + p.extension().string())).string());
  }
  return paths;
}

struct SolveCommandOptions {
  std::string scenePath, outputPath, reportPath, gridReportPath, gridImagePath;
  int gridSamples = 16384;
  RadiosityCommandOptions radiosity;
  ColourCommandOptions colour;
  uint64_t seed = 1;
  int threads = 0;
  bool quiet = false;
  CheckpointCommandOptions checkpoint;
};
}  // namespace

CommandRunner addSolveCommand(CLI::App &app) {
  auto o = std::make_shared<SolveCommandOptions>();
  app.add_option("scene", o->scenePath,
                 "Scene file: JSON (docs/scene-format.md), a bare .obj model or a glTF 2.0 file (.gltf, .glb)")
      ->required();
  app.add_option("-o,--output", o->outputPath, "Save the solution (docs/solution-format.md), e.g. scene.rad");
  app.add_option("--report", o->reportPath,
                 "Write a CSV with one row per object: area, mean radiosity and irradiance (W/m²), "
                 "luminance (cd/m²) and illuminance (lux)");
  app.add_option("--grid-report", o->gridReportPath,
                 "Write a CSV with the illuminance (lux) at every point of the scene's calculation grids and a "
                 "summary per grid: E_min, E_avg, E_max, U0, Ud (docs/scene-format.md, \"grids\")");
  app.add_option("--grid-image", o->gridImagePath,
                 "Write a false-colour plan (.png) of each calculation grid, with isolux contours and the values; "
                 "PATH-NAME.png per grid when the scene has several");
  app.add_option("--grid-samples", o->gridSamples,
                 "Most gather rays per grid point (fewer where the standard error is already below 0.5 %)")
      ->default_val(16384)
      ->check(CLI::Range(1, 1 << 24));
  addRadiosityOptions(app, o->radiosity);
  addColourOptions(app, o->colour);
  app.add_option("--seed", o->seed, "Random seed of the form-factor shadow rays and the grids' gather rays")
      ->default_val(1)
      ->check(seedRange());
  app.add_option("--threads", o->threads, "Worker threads (0: all cores); does not change the solution")
      ->default_val(0)
      ->check(CLI::Range(0, 4096));
  app.add_flag("-q,--quiet", o->quiet, "No progress or summary on stderr");
  addCheckpointOptions(app, o->checkpoint, "the stochastic solver's state");

  return [o, &app]() {
    // With several MPI ranks (cluster/cluster.h) rank 0 prints and writes; every rank solves (the stochastic
    // solver splits its rays among them).
    const bool quiet = o->quiet || !cluster::isRoot();
    checkRadiosityOptions(o->radiosity, true, "");
    std::vector<OutputFile> outputs;
    if (!o->outputPath.empty()) outputs.push_back({o->outputPath, InputLocation{"--output"}});
    if (!o->reportPath.empty()) outputs.push_back({o->reportPath, InputLocation{"--report"}});
    if (!o->gridReportPath.empty()) outputs.push_back({o->gridReportPath, InputLocation{"--grid-report"}});
    if (!o->gridImagePath.empty() && std::filesystem::path(o->gridImagePath).extension() != ".png")
      throw InputError(InputLocation{"--grid-image"}, "'" + o->gridImagePath + "': expected a .png file");
    checkCheckpointOptions(o->checkpoint);
    if (!o->checkpoint.path.empty()) outputs.push_back({o->checkpoint.path, InputLocation{"--checkpoint"}});
    checkOutputFiles(outputs, {o->scenePath});
    // Ctrl-C stops the solve at its next iteration and writes nothing (but a checkpoint).
    InterruptHandler interrupts;
    const ConsolePhases phases(!quiet);  // loading, the BVH, cutting faces, meshing: util/phase.h
    Scene scene = loadScene(o->scenePath);
    const WhiteBalance balance = applyColourOptions(app, o->colour, scene);
    const bool gridsWanted = !o->gridReportPath.empty() || !o->gridImagePath.empty();
    if (gridsWanted && scene.grids.empty())
      throw InputError(InputLocation{o->gridReportPath.empty() ? "--grid-image" : "--grid-report"},
                       "the scene has no calculation grids (\"grids\", docs/scene-format.md)");
    const std::vector<std::string> gridImages =
        o->gridImagePath.empty() ? std::vector<std::string>{} : gridImagePaths(o->gridImagePath, scene.grids);
    if (!gridImages.empty()) {
      for (const std::string &path : gridImages) outputs.push_back({path, InputLocation{"--grid-image"}});
      checkOutputFiles(outputs, {o->scenePath});
    }
    if (!quiet)
      for (const std::string &warning : scene.warnings) fmt::print(stderr, "radiant: warning: {}\n", warning);
    if (!quiet)
      for (const PointLight &light : scene.lights) fmt::print(stderr, "radiant: light {}\n", describeLight(light));
    // Lights and grids alone (a luminaire layout before the room is modelled): the grids get the lights'
    // direct illuminance, and there is nothing to solve. Asked for a solution, the solve refuses as ever.
    const bool gridsAlone = scene.faces.empty() && gridsWanted && !scene.lights.empty() && o->outputPath.empty() &&
                            o->reportPath.empty() && o->checkpoint.path.empty();
    if (gridsAlone && !quiet)
      fmt::print(stderr, "radiant: the scene has no faces: the grids get the lights' direct illuminance alone\n");
    // A solve too small to share (whySolveAlone) is rank 0's alone: the other ranks end here, before the BVH,
    // and wait for it at the job's end (cluster::Session); rank 0 works as one process.
    const std::string aloneBecause = cluster::distributed() ? whySolveAlone(scene, o->radiosity) : std::string();
    if (!aloneBecause.empty() && !cluster::isRoot()) return 0;
    if (!aloneBecause.empty() && !quiet)
      fmt::print(stderr, "radiant: {} ranks: rank 0 solves alone ({})\n", cluster::size(), aloneBecause);
    std::optional<cluster::RootAlone> rootAlone;
    if (!aloneBecause.empty()) rootAlone.emplace();
    RayTracer tracer(scene);
    SolveCheckpointOptions checkpoint;
    // A spectral solve checkpoints each pass in a file of its own (FILE's stem
    // + ".passK"), kept to the end: a pass that finished is not solved again.
    const int passes = scene.spectral.enabled() ? scene.spectral.passCount() : 1;
    auto passCheckpoint = [&](int pass) {
      return scene.spectral.enabled() ? passFilePath(o->checkpoint.path, pass + 1) : o->checkpoint.path;
    };
    if (!o->checkpoint.path.empty()) {
      std::vector<std::string> files;
      for (int pass = 0; pass < passes; ++pass) files.push_back(passCheckpoint(pass));
      refuseExistingCheckpoints(o->checkpoint, files);
      checkpoint.path = o->checkpoint.path;
      checkpoint.intervalSeconds = o->checkpoint.intervalSeconds;
      checkpoint.resume = o->checkpoint.resume;
      // The job: the scene's bytes and everything that changes the solution.
      checkpoint.job = fmt::format("radiant solve {}\nscene {} {}\nsolver {}\nseed {}\n", RADIANT_VERSION, o->scenePath,
                                   fileFingerprint(o->scenePath), o->radiosity.solver, o->seed);
      const ParameterValues given = o->radiosity.parameters.given();
      for (const auto &[name, value] : given.all()) checkpoint.job += fmt::format("--{} {}\n", name, value.text);
    }
    // One solution for an RGB scene, one per pass of three wavelengths for a spectral one.
    std::vector<Solution> solutions;
    for (int pass = 0; pass < passes && !interruptRequested(); ++pass) {
      SolveCheckpointOptions passCheckpointOptions = checkpoint;
      if (scene.spectral.enabled()) {
        applySpectralPass(scene, pass);
        if (!quiet)
          fmt::print(stderr, "radiant: solving at {} ({}/{})\n", passWavelengthLabel(scene, pass), pass + 1, passes);
        if (!checkpoint.path.empty()) {
          passCheckpointOptions.path = passCheckpoint(pass);
          passCheckpointOptions.job +=
              fmt::format("pass {} of {}: {}\n", pass + 1, passes, passWavelengthLabel(scene, pass));
          passCheckpointOptions.saveWhenDone = true;
        }
      }
      if (gridsAlone)
        solutions.emplace_back();  // no faces: no ray meets a surface, nothing is reflected
      else
        solutions.push_back(solveScene(scene, tracer, o->radiosity, o->seed, o->threads, quiet, passCheckpointOptions));
    }
    if (interruptRequested()) throw Interrupted();  // between the solve's last report and here
    std::vector<GridIlluminance> grids;
    if (gridsWanted && cluster::isRoot()) {  // rank 0 alone writes them
      GridOptions gridOptions;
      gridOptions.maxSamples = o->gridSamples;
      gridOptions.minSamples = std::min(gridOptions.minSamples, o->gridSamples);
      gridOptions.seed = o->seed;
      gridOptions.threads = o->threads;
      grids = computeGridIlluminance(scene, tracer, solutions, gridOptions);
    }
    if (scene.spectral.enabled()) applySpectralColour(scene, balance);
    if (!cluster::isRoot()) return 0;
    if (cluster::distributed() && !quiet)
      fmt::print(stderr, "radiant: {} ranks; rank 0 summed {:.1f} MB with the others\n", cluster::size(),
                 cluster::bytesSummed() * 1e-6);
    if (!o->outputPath.empty()) {
      writeSolutionPasses(solutions, scene, o->outputPath);
      if (!quiet) fmt::print(stderr, "radiant: wrote {}\n", o->outputPath);
    }
    // The finished solve's checkpoint has served (written after the solution, so a failed write keeps it).
    if (!o->checkpoint.path.empty())
      for (int pass = 0; pass < passes; ++pass) std::filesystem::remove(passCheckpoint(pass));
    if (!o->reportPath.empty()) {
      writeSurfaceReport(solutions, scene, o->reportPath, balance);
      if (!quiet) fmt::print(stderr, "radiant: wrote {}\n", o->reportPath);
    }
    if (gridsWanted && !quiet)
      for (const GridIlluminance &g : grids)
        fmt::print(stderr,
                   "radiant: grid {}: E_min {:.4g} lx, E_avg {:.4g} lx, E_max {:.4g} lx, U0 {:.3f}, Ud {:.3f}\n",
                   g.grid.name, g.minimumLux, g.averageLux, g.maximumLux, g.uniformity(), g.diversity());
    if (!o->gridReportPath.empty()) {
      writeGridReport(grids, scene.metresPerUnit, o->gridReportPath, scene.lights);
      if (!quiet) fmt::print(stderr, "radiant: wrote {}\n", o->gridReportPath);
    }
    for (size_t g = 0; g < gridImages.size(); ++g) {
      std::vector<double> lux;
      for (const GridPointIlluminance &p : grids[g].points) lux.push_back(p.illuminanceLux);
      const GridPlan plan = gridPlan(lux, grids[g].grid.nu, grids[g].grid.nv);
      writePngBytes(plan.rgb, plan.width, plan.height, gridImages[g]);
      if (!quiet) fmt::print(stderr, "radiant: wrote {}\n", gridImages[g]);
    }
    return 0;
  };
}

}  // namespace radiant
