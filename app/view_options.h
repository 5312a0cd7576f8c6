// The camera and image-size flags shared by `radiant render` and `radiant
// export` (--eye, --target, --up, --fov, --width, --height): overrides of the
// scene file's camera and image, checked as the scene file's are.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "scene/scene.h"

namespace radiant {

struct ViewCommandOptions {
  std::string eye, target, up;
  std::optional<double> fov;
  std::optional<int> width, height;
};

void addViewOptions(CLI::App &app, ViewCommandOptions &options);

/// Applies the given flags to the scene's camera and image size (positions in
/// the scene's units), then checks them: image size in range, field of view
/// in (0°, 180°), camera within the ray tracer's range, eye ≠ target, up not
/// along the view. Throws InputError naming the flag.
void applyViewOptions(const ViewCommandOptions &options, Scene &scene);

}  // namespace radiant
