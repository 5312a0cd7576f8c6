// Which pixels show a light source: what `max-reflected` needs to leave the
// emitters out of its normalisation, and what render stores in its EXR so that
// `radiant tonemap` can do the same later without the scene.
#pragma once

#include <cstdint>
#include <vector>

#include "io/image.h"
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

/// The pixels a "reflecting surfaces only" statistic must skip: every pixel
/// with some emitter coverage, and its eight neighbours, because the film's
/// samples do not fall on the coverage grid and a pixel at the edge of a light
/// can hold some of its radiance while no grid ray hit it. All false when the
/// image carries no coverage.
std::vector<uint8_t> emitterPixelMask(const Image &image);

}  // namespace radiant
