// The table of rendering methods: name → factory, one line per method.
#include <fmt/format.h>

#include "render/multipass.h"
#include "render/path_tracer.h"
#include "render/radiosity_display.h"
#include "render/renderer.h"
#include "render/two_pass.h"
#include "util/error.h"

namespace radiant {

const std::vector<RendererInfo> &rendererRegistry() {
  static const std::vector<RendererInfo> table = {
      {"path", "unbiased reference path tracer (NEE + MIS, Russian roulette)", &createPathTracer, false, true},
      {"flat", "the radiosity solution, constant per element", &createFlatRadiosityDisplay, true, true},
      {"interpolate", "the radiosity solution interpolated from its nodes (the classic radiosity image)",
       &createInterpolatedRadiosityDisplay, true, true},
      {"rushmeier", "per-pixel Monte Carlo: light sample + one secondary ray reading the solution (C&W eq. 9.10)",
       &createRushmeier, true},
      {"reichert", "form factors per pixel to every element, ray-traced visibility (--ff point|mc)", &createReichert,
       true},
      {"shirley", "direct light per pixel, indirect interpolated from the solution", &createShirley, true},
      {"kok", "as shirley, plus the brightest reflectors sampled per pixel (--sources K)", &createKok, true},
      {"multipass", "progressive passes from a radiosity preview to an unbiased image with caustics (Chen et al. 1991)",
       &createMultipassPlaceholder, true},
  };
  return table;
}

const RendererInfo &findRenderer(const std::string &name) {
  std::string names;
  for (const RendererInfo &info : rendererRegistry()) {
    if (name == info.name) return info;
    names += names.empty() ? info.name : std::string(", ") + info.name;
  }
  throw InputError(InputLocation{"--method"}, fmt::format("unknown method '{}'; known methods: {}", name, names));
}

std::unique_ptr<Renderer> createRenderer(const std::string &name, const RayTracer &tracer,
                                         const RendererOptions &options) {
  return findRenderer(name).create(tracer, options);
}

}  // namespace radiant
