// Which pixels show a light source, found by tracing camera rays: what
// `max-reflected` needs to leave the emitters out of its normalisation, and
// what render stores in its EXR ("emitter" channel) so that `radiant tonemap`
// can do the same later without the scene. The display stage reads only the
// stored fraction (display/emitter_mask.h); the tracing lives here, with the
// camera and the ray tracer.
#pragma once

#include <vector>

#include "raytrace/ray_tracer.h"
#include "scene/camera.h"

namespace radiant {

/// Camera rays per pixel side for the coverage: a 4 × 4 grid of pixel
/// positions, so the fraction is a multiple of 1/16.
constexpr int kEmitterCoverageGrid = 4;

/// Per pixel (row-major from the top left), the fraction of a regular
/// kEmitterCoverageGrid² grid of camera rays through the pixel whose first hit
/// is the front (emitting) side of a surface with emission. Emitters seen only
/// through a mirror or glass do not count: what counts is the light source
/// itself in view.
std::vector<float> emitterCoverage(const RayTracer &tracer, const PinholeCamera &camera, int width, int height);

}  // namespace radiant
