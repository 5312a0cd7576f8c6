// The table of rendering methods: name → factory, one line per method.
#include <fmt/format.h>

#include "render/path_tracer.h"
#include "render/renderer.h"
#include "util/error.h"

namespace radiant {

const std::vector<RendererInfo> &rendererRegistry() {
  static const std::vector<RendererInfo> table = {
      {"path", "unbiased reference path tracer (NEE + MIS, Russian roulette)", &createPathTracer},
  };
  return table;
}

std::unique_ptr<Renderer> createRenderer(const std::string &name, const RayTracer &tracer,
                                         const RendererOptions &options) {
  std::string names;
  for (const RendererInfo &info : rendererRegistry()) {
    if (name == info.name) return info.create(tracer, options);
    names += names.empty() ? info.name : std::string(", ") + info.name;
  }
  std::string message = fmt::format("unknown method '{}'; known methods: {}", name, names);
  InputLocation where;
  where.file = "--method";
  throw InputError(where, message);
}

}  // namespace radiant
