// `radiant render --method multipass` (render/multipass.h, docs/multipass.md):
// the passes, each written as it completes.
#pragma once

#include <string>
#include <vector>

#include "display/display_mapping.h"
#include "radiosity_options.h"
#include "render/renderer.h"
#include "scene/camera.h"

namespace radiant {

struct MultipassCommand {
  std::vector<std::string> outputs;  ///< out.exr → out.pass1.exr, …, and out.exr the latest
  DisplaySettings display;
  bool describeDisplay = false;
  std::string variancePath;
  RadiosityCommandOptions radiosity;
  RendererOptions renderer;
  int samplesPerPixel = 64;
  double timeBudgetSeconds = 0;
  uint64_t seed = 1;
  int threads = 0;
  bool quiet = false;
};

/// "out.exr", 3 → "out.pass3.exr".
std::string passOutputPath(const std::string &path, int pass);

void runMultipass(const RayTracer &tracer, const PinholeCamera &camera, int width, int height,
                  const MultipassCommand &command);

}  // namespace radiant
