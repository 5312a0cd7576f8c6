// radiant solve SCENE — meshes the scene, computes its radiosity solution,
// reports it, and optionally saves it for `radiant render --solution`.
#include <fmt/format.h>

#include "colour_options.h"
#include "commands.h"
#include "interrupt_handler.h"
#include "io/output_files.h"
#include "io/solution_file.h"
#include "parameter_flags.h"
#include "radiosity/report.h"
#include "radiosity_options.h"
#include "scene/load_scene.h"
#include "scene/spectral_scene.h"
#include "util/interrupt.h"

namespace radiant {

namespace {
struct SolveCommandOptions {
  std::string scenePath, outputPath, reportPath;
  RadiosityCommandOptions radiosity;
  ColourCommandOptions colour;
  uint64_t seed = 1;
  int threads = 0;
  bool quiet = false;
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
  addRadiosityOptions(app, o->radiosity);
  addColourOptions(app, o->colour);
  app.add_option("--seed", o->seed, "Random seed of the form-factor shadow rays")->default_val(1)->check(seedRange());
  app.add_option("--threads", o->threads, "Worker threads (0: all cores); does not change the solution")
      ->default_val(0)
      ->check(CLI::Range(0, 4096));
  app.add_flag("-q,--quiet", o->quiet, "No progress or summary on stderr");

  return [o, &app]() {
    checkRadiosityOptions(o->radiosity, true, "");
    std::vector<OutputFile> outputs;
    if (!o->outputPath.empty()) outputs.push_back({o->outputPath, InputLocation{"--output"}});
    if (!o->reportPath.empty()) outputs.push_back({o->reportPath, InputLocation{"--report"}});
    checkOutputFiles(outputs, {o->scenePath});
    // Ctrl-C stops the solve at its next iteration and writes nothing.
    InterruptHandler interrupts;
    Scene scene = loadScene(o->scenePath);
    const WhiteBalance balance = applyColourOptions(app, o->colour, scene);
    if (!o->quiet)
      for (const std::string &warning : scene.warnings) fmt::print(stderr, "radiant: warning: {}\n", warning);
    RayTracer tracer(scene);
    // One solution for an RGB scene, one per pass of three wavelengths for a spectral one.
    const int passes = scene.spectral.enabled() ? scene.spectral.passCount() : 1;
    std::vector<Solution> solutions;
    for (int pass = 0; pass < passes; ++pass) {
      if (scene.spectral.enabled()) {
        applySpectralPass(scene, pass);
        if (!o->quiet)
          fmt::print(stderr, "radiant: solving at {} ({}/{})\n", passWavelengthLabel(scene, pass), pass + 1, passes);
      }
      solutions.push_back(solveScene(scene, tracer, o->radiosity, o->seed, o->threads, o->quiet));
    }
    if (scene.spectral.enabled()) applySpectralColour(scene, balance);
    if (interruptRequested()) throw Interrupted();  // between the solve's last report and here
    if (!o->outputPath.empty()) {
      writeSolutionPasses(solutions, scene, o->outputPath);
      if (!o->quiet) fmt::print(stderr, "radiant: wrote {}\n", o->outputPath);
    }
    if (!o->reportPath.empty()) {
      writeSurfaceReport(solutions, scene, o->reportPath, balance);
      if (!o->quiet) fmt::print(stderr, "radiant: wrote {}\n", o->reportPath);
    }
    return 0;
  };
}

}  // namespace radiant
