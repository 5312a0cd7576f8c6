#pragma once

#include "render/renderer.h"

namespace radiant {

std::unique_ptr<Renderer> createFlatRadiosityDisplay(const RayTracer &tracer, const RendererOptions &options);
std::unique_ptr<Renderer> createInterpolatedRadiosityDisplay(const RayTracer &tracer, const RendererOptions &options);

}  // namespace radiant
