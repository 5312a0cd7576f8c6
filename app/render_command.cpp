// radiant render SCENE — loads a scene (JSON or bare OBJ), applies command-line
// overrides, renders with the chosen method and writes the images.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "checkpoint_options.h"
#include "cluster/cluster.h"
#include "colour_options.h"
#include "commands.h"
#include "display_options.h"
#include "image_method_command.h"
#include "interrupt_handler.h"
#include "io/output_files.h"
#include "io/solution_file.h"
#include "job_cost.h"
#include "parameter_flags.h"
#include "phase_console.h"
#include "radiosity_options.h"
#include "raytrace/ray_tracer.h"
#include "render/driver.h"
#include "render/multipass.h"
#include "render/pilot.h"
#include "render/registry.h"
#include "render/renderer.h"
#include "render/spectral_film.h"
#include "scene/load_scene.h"
#include "scene/spectral_scene.h"
#include "util/error.h"
#include "util/file_extension.h"
#include "util/interrupt.h"
#include "view_options.h"

namespace radiant {

namespace {

/// Where an interrupted render writes `path`: there, unless a file is
/// already there, which may hold a finished image and is never replaced by
/// fewer samples (issue 38); then beside it, as NAME.interrupted.EXT.
std::string pathForInterruptedImage(const std::string &path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return path;
  const std::filesystem::path p(path);
  return (p.parent_path() / (p.stem().string() + ".interrupted" + p.extension().string())).string();
}

struct RenderCommandOptions {
  std::string scenePath;
  std::string method = "path";
  std::vector<std::string> outputs;
  std::string variancePath;
  std::optional<int> spp;
  std::optional<double> time;
  std::optional<uint64_t> seed;
  ViewCommandOptions view;
  std::string pixel;
  int threads = 0;
  bool quiet = false;
  std::string solutionPath;
  RadiosityCommandOptions radiosity;
  ParameterFlags methodParameters;  ///< every method's own (render/registry.h)
  std::string selectiveMapPath;
  DisplayCommandOptions display;  ///< the PNG outputs' display mapping
  ColourCommandOptions colour;    ///< spectral scenes
  std::string quantity = "radiance";
  CheckpointCommandOptions checkpoint;
};

InputLocation flag(const std::string &name) {
  return InputLocation{name};
}

/// The default output name: the scene's folder for `…/name/scene.json`, else the file's stem.
std::string defaultStem(const std::string &scenePath) {
  std::filesystem::path p(scenePath);
  if (p.stem() == "scene" && p.has_parent_path() && !p.parent_path().filename().empty())
    return p.parent_path().filename().string();
  return p.stem().string();
}

/// --selective-map: the film's selective channel (the work each pixel's
/// samples triggered, on average), grey from none to the most.
void writeSelectiveMap(const Film &film, const std::string &channelName, const std::string &path) {
  const FilmChannel &channel = *film.channel(channelName);
  std::vector<double> work(film.pixelCount());
  double most = 0;
  for (size_t p = 0; p < work.size(); ++p) {
    work[p] = film.samples[p] ? channel.sum[p][0] / film.samples[p] : 0.0;
    most = std::max(most, work[p]);
  }
  Image map;
  map.width = film.width, map.height = film.height;
  map.rgb.resize(work.size() * 3);
  for (size_t i = 0; i < work.size(); ++i)
    for (int c = 0; c < 3; ++c) map.rgb[i * 3 + c] = float(most > 0 ? work[i] / most : 0.0);
  writeImage(map, path);
  // Element mode: each pixel's value is the fraction of its samples re-evaluated, so their mean is the share of
  // the image's area that was; link mode: the links per sample, on average and at most.
  double total = 0;
  for (double w : work) total += w;
  const double mean = total / double(std::max<size_t>(1, work.size()));
  if (channelName == "selective-links")
    fmt::print(stderr, "radiant: selective map {}: {:.3g} links per pixel on average, at most {:.3g}\n", path, mean,
               most);
  else
    fmt::print(stderr, "radiant: selective map {}: {:.1f}% of the image re-evaluated\n", path, 100 * mean);
}

/// What a checkpoint must belong to (render/checkpoint.h): the scene file's and
/// solution's bytes and every setting that changes the pixels. Not the
/// models, textures or photometric files the scene names: those are the
/// user's to keep.
std::string checkpointJob(const RenderCommandOptions &o, const Scene &scene, const ParameterValues &given) {
  const RenderSettings &r = scene.render;
  const CameraSettings &c = scene.camera;
  std::string job = fmt::format(
      "radiant render {}\nscene {} {}\nsolution {}\nmethod {}\nimage {}x{}\nspp {} time {} seed {}\nquantity {}\n"
      "camera {} {} {} {} {} {} {} {} {} {}\n",
      RADIANT_VERSION, o.scenePath, fileFingerprint(o.scenePath), fileFingerprint(o.solutionPath), o.method, r.width,
      r.height, r.samplesPerPixel, r.timeBudgetSeconds, r.seed, o.quantity, c.eye.x, c.eye.y, c.eye.z, c.target.x,
      c.target.y, c.target.z, c.up.x, c.up.y, c.up.z, c.verticalFovDegrees);
  for (const auto &[name, value] : given.all()) job += fmt::format("--{} {}\n", name, value.text);
  return job;
}

}  // namespace

CommandRunner addRenderCommand(CLI::App &app) {
  auto o = std::make_shared<RenderCommandOptions>();
  app.add_option("scene", o->scenePath,
                 "Scene file: JSON (docs/scene-format.md), a bare .obj model or a glTF 2.0 file (.gltf, .glb)")
      ->required();
  std::string methods;
  for (const RendererInfo &info : rendererRegistry()) methods += fmt::format("\n  {:<12} {}", info.name, info.summary);
  app.add_option("-m,--method", o->method, "Rendering method:" + methods)->default_val("path");
  app.add_option("-o,--output", o->outputs,
                 "Output image; repeat for several. Format by extension: .exr (linear float), .pfm (linear), "
                 ".hdr (Radiance RGBE, linear), .png (display mapping: --tonemap, default linear). Default: NAME.exr "
                 "and NAME.png, NAME from the "
                 "scene file");
  app.add_option("--quantity", o->quantity,
                 "What the pixels hold: radiance (W·sr⁻¹·m⁻²) or irradiance (W·m⁻² arriving at the surface seen, for "
                 "illuminance maps: radiant tonemap --falsecolor --quantity illuminance); irradiance with path, flat "
                 "and interpolate")
      ->default_val("radiance")
      ->check(CLI::IsMember({"radiance", "irradiance"}));
  app.add_option("--variance", o->variancePath, "Also write the variance of each pixel's mean (.exr or .pfm)");
  app.add_option("--spp", o->spp,
                 "Samples per pixel (default: the scene's render.spp, else 64; flat and interpolate at least 1024, "
                 "their smooth pixels stopping after 8)");
  app.add_option("--time", o->time,
                 "Time budget in seconds: stop after the sampling round that reaches it (--spp still caps it)");
  app.add_option("--seed", o->seed, "Random seed; the same seed and sample count give the same image")
      ->check(seedRange());
  app.add_option("--threads", o->threads, "Worker threads (0: all cores); does not change the image")
      ->default_val(0)
      ->check(CLI::Range(0, 4096));
  addViewOptions(app, o->view);
  app.add_option("--pixel", o->pixel, "Render only pixel x,y (debugging; other pixels stay black)");
  app.add_flag("-q,--quiet", o->quiet, "No progress or summary on stderr");
  app.add_option("--solution", o->solutionPath,
                 "Radiosity solution from `radiant solve -o` to display instead of solving (methods that read one)");
  addRadiosityOptions(app, o->radiosity);
  app.add_option("--selective-map", o->selectiveMapPath,
                 "--selective: write a PNG of the pixels re-evaluated (white) or, in link mode, how many links");
  std::vector<ParameterGroup> groups;
  for (const RendererInfo &info : rendererRegistry())
    groups.push_back({fmt::format("--method {}", info.name), &info.parameters});
  o->methodParameters.add(app, groups);
  addDisplayOptions(app, o->display);
  addColourOptions(app, o->colour);
  addCheckpointOptions(app, o->checkpoint, "the render's state");

  return [o, &app]() {
    // With several MPI ranks (cluster/cluster.h) rank 0 prints and writes; every rank renders its share.
    const bool quiet = o->quiet || !cluster::isRoot();
    {
      const RendererInfo &method = findRenderer(o->method);
      bool solving = method.needsSolution && o->solutionPath.empty();
      checkRadiosityOptions(o->radiosity, solving,
                            method.needsSolution ? "the solution comes from --solution"
                                                 : "--method " + o->method + " does not read a radiosity solution");
      if (!o->solutionPath.empty() && !method.needsSolution)
        throw InputError(InputLocation{"--solution"}, "--method " + o->method + " does not read a radiosity solution");
      // Every given method parameter is one the method declares, of its type and in its range.
      const Parameters parameters = methodParameters(method, o->methodParameters.given());
      if (o->quantity == "irradiance" && !method.supportsIrradiance) {
        std::string which;
        for (const RendererInfo &info : rendererRegistry())
          if (info.supportsIrradiance) which += (which.empty() ? "" : ", ") + std::string(info.name);
        throw InputError(flag("--quantity"),
                         fmt::format("irradiance images come from --method {}, not {}", which, o->method));
      }
      if (!o->selectiveMapPath.empty() &&
          !(o->methodParameters.given().has("selective") && parameters.flag("selective")))
        throw InputError(flag("--selective-map"), "needs --selective");
      if (!o->selectiveMapPath.empty() && std::filesystem::path(o->selectiveMapPath).extension() != ".png")
        throw InputError(flag("--selective-map"), "'" + o->selectiveMapPath + "': expected a .png file");
      checkCheckpointOptions(o->checkpoint);
    }
    // Every output checked before any work: a long render must not end in "cannot write".
    std::vector<std::string> outputs = o->outputs;
    if (outputs.empty()) {
      std::string stem = defaultStem(o->scenePath);
      outputs = {stem + ".exr", stem + ".png"};
    }
    for (const std::string &path : outputs)
      if (!isSupportedImageExtension(path))
        throw InputError(flag("--output"),
                         "'" + path + "': unknown image extension (expected .exr, .pfm, .hdr or .png)");
    // A variance is a linear quantity in (W·sr⁻¹·m⁻²)²: a display-mapped PNG of it would say nothing.
    if (!o->variancePath.empty() && !isLinearImageExtension(o->variancePath))
      throw InputError(flag("--variance"), "'" + o->variancePath + "': expected a .exr, .pfm or .hdr file");
    {
      std::vector<OutputFile> files;
      for (const std::string &path : outputs) files.push_back({path, flag("--output")});
      if (!o->variancePath.empty()) files.push_back({o->variancePath, flag("--variance")});
      if (!o->selectiveMapPath.empty()) files.push_back({o->selectiveMapPath, flag("--selective-map")});
      if (!o->checkpoint.path.empty()) files.push_back({o->checkpoint.path, flag("--checkpoint")});
      checkOutputFiles(files, {o->scenePath, o->solutionPath});
    }
    // Ctrl-C: the image so far is written (with its sample count), then exit 130.
    InterruptHandler interrupts;
    const ConsolePhases phases(!quiet);  // loading, the BVH, cutting faces, meshing: util/phase.h
    Scene scene = loadScene(o->scenePath);
    const WhiteBalance balance = applyColourOptions(app, o->colour, scene);
    applyViewOptions(o->view, scene);
    if (o->spp) scene.render.samplesPerPixel = *o->spp;
    if (o->time) scene.render.timeBudgetSeconds = *o->time;
    if (o->seed) scene.render.seed = *o->seed;
    if (o->time && !o->spp) scene.render.samplesPerPixel = kMaxSamplesPerPixel;  // the budget decides
    if (!o->time && !o->spp)  // a method whose samples only antialias takes more (RendererInfo)
      scene.render.samplesPerPixel =
          std::max(scene.render.samplesPerPixel, findRenderer(o->method).defaultSamplesPerPixel);

    // Command-line values get the same checks as the scene file's, before any allocation.
    const RenderSettings &r = scene.render;
    if (r.samplesPerPixel < 1 || r.samplesPerPixel > kMaxSamplesPerPixel)
      throw InputError(flag("--spp"), fmt::format("samples per pixel must be in 1..{}, got {}", kMaxSamplesPerPixel,
                                                  r.samplesPerPixel));
    if (!(r.timeBudgetSeconds >= 0) || !std::isfinite(r.timeBudgetSeconds))
      throw InputError(flag("--time"), "the time budget must be a non-negative number of seconds");
    // Before any solve: what the image will hold, refused if it cannot fit.
    RenderJobSize job;
    job.width = r.width, job.height = r.height;
    job.samplesPerPixel = r.samplesPerPixel;
    job.timeBudget = r.timeBudgetSeconds > 0;
    job.passes = scene.spectral.enabled() ? scene.spectral.passCount() : 1;
    job.channels = o->selectiveMapPath.empty() ? 0 : 1;
    job.outputs = int(outputs.size()) + (o->variancePath.empty() ? 0 : 1);
    announceRenderJob(job, quiet);

    const DisplaySettings display = renderDisplaySettings(app, o->display, r.exposure, outputs);

    DriverOptions driver;
    driver.samplesPerPixel = r.samplesPerPixel;
    driver.timeBudgetSeconds = r.timeBudgetSeconds;
    driver.seed = r.seed;
    driver.threads = o->threads;
    if (!o->pixel.empty()) {
      int x = -1, y = -1;
      char comma = 0;
      std::istringstream in(o->pixel);
      if (!(in >> x >> comma >> y) || comma != ',' || x < 0 || y < 0 || x >= r.width || y >= r.height)
        throw InputError(flag("--pixel"), fmt::format("expected x,y inside the {}x{} image", r.width, r.height));
      driver.onlyPixelX = x;
      driver.onlyPixelY = y;
    }

    if (!quiet)
      for (const std::string &warning : scene.warnings) fmt::print(stderr, "radiant: warning: {}\n", warning);

    const RendererInfo &method = findRenderer(o->method);
    RayTracer tracer(scene);  // geometry only: a spectral pass changes the materials, not the rays
    PinholeCamera camera(scene.camera, r.width, r.height);
    // The scene file's render.max_depth, for the methods that have the parameter.
    ParameterValues given = o->methodParameters.given();
    const bool takesMaxDepth = std::any_of(method.parameters.begin(), method.parameters.end(),
                                           [](const ParameterSpec &s) { return s.name == "max-depth"; });
    if (takesMaxDepth && !given.has("max-depth") && r.maxDepth != 0) {
      InputLocation where{o->scenePath};
      where.jsonPath = "/render/max_depth";
      given.set("max-depth", std::to_string(r.maxDepth), where);
    }
    const Parameters parameters = methodParameters(method, given);
    // A spectral render checkpoints each pass in a file of its own (FILE's
    // stem + ".passK"), kept to the end: a pass that finished is not redone.
    // The stochastic solve a method needs checkpoints beside it (".solve",
    // ".solveK"), and keeps its final state until the image is written, so
    // that a render stopped in its image phase does not solve again.
    const int passCount = scene.spectral.enabled() ? scene.spectral.passCount() : 1;
    auto passCheckpoint = [&](int pass) {
      return scene.spectral.enabled() ? passFilePath(o->checkpoint.path, pass + 1) : o->checkpoint.path;
    };
    auto solveCheckpoint = [&](int pass) {
      return suffixedFilePath(o->checkpoint.path,
                              scene.spectral.enabled() ? fmt::format(".solve{}", pass + 1) : ".solve");
    };
    const bool checkpointedSolve = !o->checkpoint.path.empty() && method.needsSolution && !method.render &&
                                   o->solutionPath.empty() && chooseSolver(scene, o->radiosity).solver == "stochastic";
    if (!o->checkpoint.path.empty()) {
      std::vector<std::string> files;
      for (int pass = 0; pass < passCount; ++pass)
        files.insert(files.end(), {passCheckpoint(pass), solveCheckpoint(pass)});
      refuseExistingCheckpoints(o->checkpoint, files);
      driver.checkpointPath = o->checkpoint.path;
      driver.checkpointIntervalSeconds = o->checkpoint.intervalSeconds;
      driver.resume = o->checkpoint.resume;
      driver.checkpointJob = checkpointJob(*o, scene, given);
    }
    if (method.render) {  // a method that owns its loop: passes, each written as it completes
      if (scene.spectral.enabled())
        throw InputError(flag("--method"), o->method + " does not run spectral scenes yet: use --colour rgb");
      if (!o->solutionPath.empty())
        throw InputError(flag("--solution"), o->method + " solves itself: a progressive preview, then --solver");
      ImageMethodCommand command{outputs, display, app.count("--tonemap") > 0, o->variancePath, quiet};
      ImageJob job{tracer, camera, r.width, r.height};
      job.pixelAngle = pixelAngle(scene.camera, r.height);
      job.samplesPerPixel = r.samplesPerPixel;
      job.timeBudgetSeconds = r.timeBudgetSeconds;
      job.seed = r.seed;
      job.threads = o->threads;
      job.checkpointPath = driver.checkpointPath, job.checkpointJob = driver.checkpointJob;
      job.checkpointIntervalSeconds = driver.checkpointIntervalSeconds, job.resume = driver.resume;
      job.solve = [&](int maxShots) {
        if (maxShots > 0) return solvePreview(scene, tracer, o->radiosity, maxShots, r.seed, o->threads);
        RadiosityCommandOptions radiosity = o->radiosity;
        radiosity.solver = multipassSolverName(radiosity.solver, r.timeBudgetSeconds);
        return solveScene(scene, tracer, radiosity, r.seed, o->threads, quiet);
      };
      runImageMethod(method, parameters, job, command);
      return interruptRequested() ? interruptedExitStatus() : 0;
    }
    std::vector<Solution> solutions;
    if (method.needsSolution && !o->solutionPath.empty()) solutions = readSolutionPasses(o->solutionPath, scene);

    // One pass for an RGB scene; ⌈N/3⌉ for a spectral one, each at three of its wavelengths.
    const bool spectral = scene.spectral.enabled();
    const int passes = spectral ? scene.spectral.passCount() : 1;
    RenderStats stats;
    bool selectiveMapWritten = false;
    auto renderPass = [&](int pass, Film &film) {
      if (stats.interrupted) return;  // a stopped spectral render starts no further pass
      const std::string label =
          spectral ? fmt::format("{} {} ({}/{})", o->method, passWavelengthLabel(scene, pass), pass + 1, passes)
                   : o->method;
      RenderContext context;
      context.irradiance = o->quantity == "irradiance";
      context.pixelSpreadAngle = texturePixelSpread(scene.camera, r.height, r.samplesPerPixel);
      Solution solved;
      if (method.needsSolution) {
        if (solutions.empty()) {
          if (!quiet && spectral) fmt::print(stderr, "radiant: solving at {}\n", passWavelengthLabel(scene, pass));
          SolveCheckpointOptions solveState;
          if (checkpointedSolve) {
            solveState.path = solveCheckpoint(pass);
            solveState.intervalSeconds = o->checkpoint.intervalSeconds;
            solveState.resume = o->checkpoint.resume;
            solveState.job = fmt::format("{}solve of pass {}\n", driver.checkpointJob, pass + 1);
            solveState.saveWhenDone = true;
          }
          solved = solveScene(scene, tracer, o->radiosity, r.seed, o->threads, quiet, solveState);
        }
        context.solution = solutions.empty() ? &solved : &solutions[pass];
      }
      std::unique_ptr<Renderer> renderer = createRenderer(o->method, tracer, context, given);
      // A large job's time, from a pilot of a fraction of a second before its first sample (after any solve).
      if (pass == 0 && !quiet && !job.timeBudget && isLargeRenderJob(job))
        announceRenderTime(job, measureSampleRate(camera, *renderer, r.width, r.height, o->threads, 0.3),
                           renderer->variesOnlyAcrossThePixel(), cluster::size());
      // --selective-map: the renderer's selective channel, in the first pass with light.
      std::string mapChannel;
      if (!o->selectiveMapPath.empty() && !selectiveMapWritten)
        for (const std::string &name : renderer->channels())
          if (name.rfind("selective-", 0) == 0) mapChannel = name;
      if (!mapChannel.empty()) film = Film(film.width, film.height, {mapChannel});
      DriverOptions passDriver = driver;
      passDriver.timeBudgetSeconds = driver.timeBudgetSeconds / passes;  // --time covers all passes
      if (spectral && !driver.checkpointPath.empty()) {
        passDriver.checkpointPath = passCheckpoint(pass);
        passDriver.checkpointJob +=
            fmt::format("pass {} of {}: {}\n", pass + 1, passes, passWavelengthLabel(scene, pass));
        passDriver.checkpointWhenDone = true;
      }
      RenderStats passStats =
          renderImage(camera, *renderer, passDriver, film, quiet ? ProgressCallback{} : makeConsoleProgress(label));
      stats.samplesPerPixel = std::max(stats.samplesPerPixel, passStats.samplesPerPixel);
      stats.seconds += passStats.seconds;
      stats.cameraSamples += passStats.cameraSamples;
      stats.interrupted = stats.interrupted || passStats.interrupted;
      if (passStats.resumedFromSamples >= 0 && !quiet)
        fmt::print(stderr, "radiant: resumed from {} ({} spp done)\n", passDriver.checkpointPath,
                   passStats.resumedFromSamples);
      if (!mapChannel.empty() && cluster::isRoot()) {
        writeSelectiveMap(film, mapChannel, o->selectiveMapPath);
        selectiveMapWritten = true;
      }
    };
    SpectralImages rendered = renderPasses(scene, r.width, r.height, balance, renderPass);
    // A spectral image needs every pass's wavelengths: one cut short has no colour to write. A render
    // stopped in its first round (0 spp: some pixels without a sample) has no image either, and
    // writing its film would replace an earlier file of that name with a black one (issue 38).
    if (stats.interrupted && (spectral || stats.samplesPerPixel == 0)) throw Interrupted();
    Image &image = rendered.colour;
    image.quantity = o->quantity;
    image.samplesPerPixel = stats.samplesPerPixel;
    image.interrupted = stats.interrupted;
    rendered.variance.samplesPerPixel = stats.samplesPerPixel;
    rendered.variance.interrupted = stats.interrupted;
    if (driver.onlyPixelX >= 0 && !quiet) {
      const float *v = image.pixel(driver.onlyPixelX, driver.onlyPixelY);
      fmt::print(stderr, "pixel {},{}: {} {:.6g} {:.6g} {:.6g} {}{}\n", driver.onlyPixelX, driver.onlyPixelY,
                 o->quantity, v[0], v[1], v[2], o->quantity == "radiance" ? "W/(sr·m²)" : "W/m²",
                 spectral ? " (linear sRGB from the spectrum)" : "");
    }
    if (!cluster::isRoot()) return stats.interrupted ? interruptedExitStatus() : 0;
    std::string variancePath = o->variancePath;
    std::vector<std::string> kept;  // earlier files an interrupted render wrote beside
    auto besideAnEarlierFile = [&](std::string &path) {
      const std::string beside = pathForInterruptedImage(path);
      if (beside != path) kept.push_back(path), path = beside;
    };
    if (stats.interrupted) {
      for (std::string &path : outputs) besideAnEarlierFile(path);
      if (!variancePath.empty()) besideAnEarlierFile(variancePath);
    }
    writeRenderOutputs(image, outputs, display, app.count("--tonemap") > 0, tracer, camera, quiet);
    if (!variancePath.empty()) writeImage(rendered.variance, variancePath);
    // A finished render's checkpoint has served; a stopped one's is what --resume reads.
    if (!o->checkpoint.path.empty() && !stats.interrupted)
      for (int pass = 0; pass < passes; ++pass) {
        std::filesystem::remove(passCheckpoint(pass));
        std::filesystem::remove(solveCheckpoint(pass));
      }
    if (!quiet) {
      // Converged pixels may have stopped early (render/driver.h): say what the mean pixel took.
      const double pixelsTaken = double(r.width) * r.height * (spectral ? passes : 1);
      const double mean = driver.onlyPixelX >= 0 ? stats.samplesPerPixel : stats.cameraSamples / pixelsTaken;
      const std::string converged =
          mean < stats.samplesPerPixel - 0.5 ? fmt::format(" (converged pixels stopped: {:.1f} on average)", mean) : "";
      if (cluster::distributed())
        fmt::print(stderr, "radiant: {} ranks; rank 0 summed {:.1f} MB with the others\n", cluster::size(),
                   cluster::bytesSummed() * 1e-6);
      fmt::print(stderr, "radiant: {}{} spp{}{} in {:.2f} s ({:.3g} Msamples/s); wrote {}\n",
                 stats.interrupted ? "interrupted after " : "", stats.samplesPerPixel,
                 spectral ? fmt::format(" × {} passes", passes) : std::string(), converged, stats.seconds,
                 stats.cameraSamples / std::max(stats.seconds, 1e-9) * 1e-6, fmt::join(outputs, ", "));
      if (!kept.empty())
        fmt::print(stderr, "radiant: kept the earlier {} (an interrupted render never replaces a file)\n",
                   fmt::join(kept, ", "));
    }
    return stats.interrupted ? interruptedExitStatus() : 0;
  };
}

}  // namespace radiant
