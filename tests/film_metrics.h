// Image comparisons shared by the tests that measure a method against the path tracer.
#pragma once

#include <cmath>

#include "render/film.h"

namespace radiant::test {

/// Mean relative error of the block sums (block × block pixels, band average)
/// of `test` against `reference`: blocks compare light, not per-pixel noise.
/// Blocks the reference leaves black are skipped. Sizes must match.
inline double meanBlockError(const Film &test, const Film &reference, int block = 8) {
  double sum = 0;
  int blocks = 0;
  for (int by = 0; by + block <= reference.height; by += block)
    for (int bx = 0; bx + block <= reference.width; bx += block) {
      double t = 0, r = 0;
      for (int y = by; y < by + block; ++y)
        for (int x = bx; x < bx + block; ++x) {
          const size_t p = size_t(y) * reference.width + x;
          t += test.mean(p).average();
          r += reference.mean(p).average();
        }
      if (r <= 0) continue;
      sum += std::abs(t - r) / r;
      ++blocks;
    }
  return blocks ? sum / blocks : 0.0;
}

}  // namespace radiant::test
