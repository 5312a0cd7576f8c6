// What a render will hold in memory, said before it starts when the job is
// large, and refused when it cannot fit (issue 38: 16384×4096 on a large
// model was accepted without a word).
#pragma once

#include <cstddef>
#include <optional>

#include "render/pilot.h"

namespace radiant {

struct RenderJobSize {
  int width = 0, height = 0;
  int samplesPerPixel = 0;
  bool timeBudget = false;  ///< --time decides the samples; samplesPerPixel is only their ceiling
  int passes = 1;           ///< spectral passes, each with its film's image kept to the end
  int channels = 0;         ///< extra film channels (the selective map's)
  int outputs = 1;          ///< image files written, each converted from the film once
};

/// Bytes the film, the passes' images and the outputs hold at once: a lower
/// bound of the render's memory (the scene, its BVH and any solution come on top).
double renderImageBytes(const RenderJobSize &job);

/// The memory the kernel says is available (MemAvailable), or the process's
/// own limit (ulimit -v) where that is less, bytes; none when neither is known.
std::optional<double> availableMemoryBytes();

/// ≥ 16 M pixels, ≥ 1 GB of film and images, or ≥ 10¹⁰ samples (without a --time budget).
bool isLargeRenderJob(const RenderJobSize &job);

/// Throws InputError at --width/--height when renderImageBytes exceeds the
/// available memory; else, for a large job (≥ 16 M pixels, ≥ 1 GB, or
/// ≥ 10¹⁰ samples), prints one line of what it holds and traces, unless quiet.
void announceRenderJob(const RenderJobSize &job, bool quiet);

/// The time a large job's sampling will take, from the rate of a pilot
/// (render/pilot.h) on one of `ranks` alike: one line on stderr. `atMost`
/// for a method whose pixels stop early where they have converged
/// (Renderer::variesOnlyAcrossThePixel): then it is an upper bound.
void announceRenderTime(const RenderJobSize &job, const PilotRate &pilot, bool atMost, int ranks);

}  // namespace radiant
