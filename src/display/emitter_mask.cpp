#include "display/emitter_mask.h"

namespace radiant {

std::vector<uint8_t> emitterPixelMask(const Image &image) {
  const int w = image.width, h = image.height;
  std::vector<uint8_t> mask(size_t(w) * h, 0);
  if (image.emitterFraction.size() != mask.size()) return mask;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!(image.emitterFraction[size_t(y) * w + x] > 0)) continue;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          int nx = x + dx, ny = y + dy;
          if (nx >= 0 && ny >= 0 && nx < w && ny < h) mask[size_t(ny) * w + nx] = 1;
        }
    }
  return mask;
}

}  // namespace radiant
