// The table of rendering methods, one line per method. Each method's file
// defines its entry (name, summary, parameters, factory); adding a method is
// that file and one line here (docs/adding-a-method.md).
#include "render/registry.h"

#include <fmt/format.h>

#include "util/error.h"

namespace radiant {

RendererInfo pathMethod();         // path_tracer.cpp
RendererInfo flatMethod();         // radiosity_display.cpp
RendererInfo interpolateMethod();  // radiosity_display.cpp
RendererInfo rushmeierMethod();    // rushmeier.cpp
RendererInfo reichertMethod();     // reichert.cpp
RendererInfo shirleyMethod();      // shirley.cpp
RendererInfo kokMethod();          // shirley.cpp
RendererInfo multipassMethod();    // multipass.cpp

const std::vector<RendererInfo> &rendererRegistry() {
  static const std::vector<RendererInfo> table = {
      pathMethod(),     flatMethod(),    interpolateMethod(), rushmeierMethod(),
      reichertMethod(), shirleyMethod(), kokMethod(),         multipassMethod(),
  };
  return table;
}

const RendererInfo &findRenderer(const std::string &name) {
  std::string names;
  for (const RendererInfo &info : rendererRegistry()) {
    if (name == info.name) return info;
    names += names.empty() ? info.name : std::string(", ") + info.name;
  }
  throw InputError(InputLocation::ofParameter("method"),
                   fmt::format("unknown method '{}'; known methods: {}", name, names));
}

Parameters methodParameters(const RendererInfo &method, const ParameterValues &given) {
  std::vector<std::pair<std::string, const ParameterTable *>> others;
  for (const RendererInfo &info : rendererRegistry()) others.push_back({info.name, &info.parameters});
  checkParameters(method.parameters, given, fmt::format("method {}", method.name), others);
  return Parameters(method.parameters, given);
}

std::unique_ptr<Renderer> createRenderer(const std::string &name, const RayTracer &tracer, const RenderContext &context,
                                         const ParameterValues &given) {
  const RendererInfo &method = findRenderer(name);
  if (!method.create)
    throw InputError(InputLocation::ofParameter("method"),
                     fmt::format("{} runs its own passes (RendererInfo::render), not one camera ray at a time", name));
  return method.create(tracer, context, methodParameters(method, given));
}

}  // namespace radiant
