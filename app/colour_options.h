// Options of spectral scenes shared by `radiant solve` and `radiant render`
// (docs/spectral.md): run the spectra, or their sRGB colours, and the white.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "colour/spectrum.h"
#include "scene/scene.h"

namespace radiant {

struct ColourCommandOptions {
  std::string colour = "spectral";    ///< spectral | rgb
  std::string whiteBalance = "none";  ///< none | equal-energy
};

void addColourOptions(CLI::App &app, ColourCommandOptions &options);

/// Checks the flags against the scene (they apply to spectral scenes only) and,
/// for --colour rgb, turns the scene into an RGB one. Returns the white balance.
WhiteBalance applyColourOptions(const CLI::App &app, const ColourCommandOptions &options, Scene &scene);

}  // namespace radiant
