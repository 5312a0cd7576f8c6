// The display mapping of the export tests: linear, exposure 0, so that a
// baked vertex's display value is its radiance (clamped to [0, 1]).
#pragma once

#include <algorithm>

namespace radiant::test {

inline void identityDisplay(const float radiance[3], double display[3]) {
  for (int c = 0; c < 3; ++c) display[c] = std::clamp(double(radiance[c]), 0.0, 1.0);
}

}  // namespace radiant::test
