// The pixels a "reflecting surfaces only" statistic skips, from the emitter
// coverage an image carries (Image::emitterFraction, computed at render time
// by render/emitter_coverage.h and stored in the EXR's "emitter" channel).
#pragma once

#include <cstdint>
#include <vector>

#include "io/image.h"

namespace radiant {

/// Every pixel with some emitter coverage, and its eight neighbours, because
/// the film's samples do not fall on the coverage grid and a pixel at the edge
/// of a light can hold some of its radiance while no grid ray hit it. All
/// false when the image carries no coverage.
std::vector<uint8_t> emitterPixelMask(const Image &image);

}  // namespace radiant
