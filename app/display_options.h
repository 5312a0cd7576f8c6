// The display-mapping flags shared by `radiant tonemap` and `radiant render`
// (docs/tone-mapping.md): the tone operator and its parameters, the transfer
// curve, the bit depth and the out-of-gamut rule.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "display/display_mapping.h"
#include "io/image.h"
#include "parameter_flags.h"
#include "raytrace/ray_tracer.h"
#include "scene/camera.h"

namespace radiant {

struct DisplayCommandOptions {
  std::string toneOperator = "linear";
  ParameterFlags toneParameters;  ///< the operators' own, from their tables (display/tone_operator.h)
  std::optional<double> gamma;
  bool srgb = false;
  int bits = 8;
  std::string gamut = "clip";
};

void addDisplayOptions(CLI::App &app, DisplayCommandOptions &options);

/// The settings the flags ask for. A flag the chosen operator does not use is
/// an error naming it. `defaultExposureStops` is what `linear`
/// uses without --exposure (render: the scene's render.exposure).
DisplaySettings displaySettings(const CLI::App &app, const DisplayCommandOptions &options, double defaultExposureStops);

/// render: displaySettings with the scene's exposure, and refused (naming the
/// flag) when display flags are given but no output is a PNG.
DisplaySettings renderDisplaySettings(const CLI::App &app, const DisplayCommandOptions &options,
                                      double sceneExposureStops, const std::vector<std::string> &outputs);

/// Prints the operator's constants (when `describe`) and its warnings to stderr.
void reportDisplayMapping(const DisplayMapping &mapping, bool describe);

/// render's outputs: EXR and PFM get the linear radiance (the EXR with the
/// emitter coverage channel), PNG the display mapping. `coverage`, when
/// given, caches the emitter coverage between calls for the same camera
/// (one ray per pixel: traced once, not once per pass).
void writeRenderOutputs(Image &image, const std::vector<std::string> &outputs, const DisplaySettings &display,
                        bool describeDisplay, const RayTracer &tracer, const PinholeCamera &camera, bool quiet,
                        std::vector<float> *coverage = nullptr);

}  // namespace radiant
