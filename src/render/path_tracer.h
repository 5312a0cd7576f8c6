#pragma once

#include "render/renderer.h"

namespace radiant {

std::unique_ptr<Renderer> createPathTracer(const RayTracer &tracer, const RendererOptions &options);

}  // namespace radiant
