// `radiant render --method M` for a method that owns its loop (RendererInfo::render,
// e.g. multipass): each pass's image written as it completes.
#pragma once

#include <string>
#include <vector>

#include "display/display_mapping.h"
#include "render/registry.h"

namespace radiant {

struct ImageMethodCommand {
  std::vector<std::string> outputs;  ///< out.exr → out.pass1.exr, …, and out.exr the latest
  DisplaySettings display;
  bool describeDisplay = false;
  std::string variancePath;
  bool quiet = false;
};

/// Runs the method on `job` (its solve set by the caller), with outputs and progress from `command`.
void runImageMethod(const RendererInfo &method, const Parameters &parameters, ImageJob job,
                    const ImageMethodCommand &command);

}  // namespace radiant
