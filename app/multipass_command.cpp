#include "multipass_command.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>

#include "display_options.h"
#include "io/image.h"
#include "render/multipass.h"

namespace radiant {

std::string passOutputPath(const std::string &path, int pass) {
  std::filesystem::path p(path);
  return (p.parent_path() / (p.stem().string() + fmt::format(".pass{}", pass) + p.extension().string())).string();
}

void runMultipass(const RayTracer &tracer, const PinholeCamera &camera, int width, int height,
                  const MultipassCommand &command) {
  MultipassOptions options;
  options.timeBudgetSeconds = command.timeBudgetSeconds;
  options.samplesPerPixel = command.samplesPerPixel;
  options.seed = command.seed;
  options.threads = command.threads;
  options.renderer = command.renderer;

  // The preview is progressive refinement, stopped after its first shots; the
  // later passes read the solution of --solver (auto by default, as every method).
  auto solve = [&](int maxShots) {
    RadiosityCommandOptions o = command.radiosity;
    if (maxShots > 0) o.solver.solver = "progressive", o.solver.maxIterations = maxShots, o.solver.importance = false;
    return solveScene(tracer.scene(), tracer, o, command.seed, command.threads, command.quiet || maxShots > 0);
  };
  auto write = [&](const MultipassPass &pass, const Image &mean, const Image &variance) {
    std::vector<std::string> paths;
    for (const std::string &path : command.outputs) paths.push_back(passOutputPath(path, pass.index));
    for (const std::string &path : command.outputs) paths.push_back(path);  // the latest pass
    Image image = mean;
    writeRenderOutputs(image, paths, command.display, command.describeDisplay && pass.index == 1, tracer, camera, true);
    if (!command.variancePath.empty()) writeImage(variance, command.variancePath);
    if (!command.quiet)
      fmt::print(stderr, "radiant: multipass {} ({}): {} spp, {:.2f} s{}{}; wrote {}\n", pass.index, pass.name,
                 pass.samplesPerPixel, pass.seconds,
                 pass.causticPhotons ? fmt::format(", {} caustic photons within {:.1f} mm", pass.causticPhotons,
                                                   pass.photonRadius * 1e3)
                                     : std::string(),
                 pass.index >= 3
                     ? fmt::format("; so far {} spp reading the solution, {} of them paired with the unbiased "
                                   "path, which weighs {:.2f} (the solution's bias {:.3g} W/(sr m²) RMS)",
                                   pass.controlSamples, pass.pairedSamples, pass.unbiasedWeight, pass.estimatedBias)
                     : std::string(),
                 fmt::join(paths, ", "));
  };
  MultipassProgress progress;
  if (!command.quiet) progress = [](const std::string &label) { return makeConsoleProgress(label); };
  renderMultipass(tracer, camera, width, height, options, solve, write, progress);
}

}  // namespace radiant
