// The rate a renderer samples an image at, measured on a pilot before a
// large job starts, so that the job's time is said before it is spent
// (issue 38: a 16384×4096 render on a 10⁵-face model started without a word
// of what it would cost; the progress line's time left comes only after the
// first tiles).
#pragma once

#include <cstddef>

#include "render/renderer.h"
#include "scene/camera.h"

namespace radiant {

struct PilotRate {
  double samplesPerSecond = 0;  ///< over all `threads` workers
  size_t samples = 0;           ///< taken by the pilot
  double seconds = 0;           ///< the pilot's own time
};

/// Samples of pixels spread over the whole image (a 64 × 64 lattice of
/// pixels, since the cost varies across it: a wall is cheap, the view
/// through glass dear), taken by `threads` workers (0: all cores) for about
/// `seconds` and at least one sample per worker. The pilot's samples are its
/// own (another seed than the image's) and go into no film: the image is the
/// same with or without it.
PilotRate measureSampleRate(const PinholeCamera &camera, const Renderer &renderer, int width, int height, int threads,
                            double seconds);

}  // namespace radiant
