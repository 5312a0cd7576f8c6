// Deterministic random numbers.
//
// PCG32 (O'Neill 2014, pcg-random.org): small state, good statistics, and
// independent streams. Every pixel sample gets its own generator seeded from
// (seed, pixel, sample index), so an image does not depend on thread count or
// on how the driver splits work into tiles and rounds.
#pragma once

#include <cstdint>

namespace radiant {

class Pcg32 {
 public:
  Pcg32() { seed(0x853c49e6748fea9bULL, 0xda3e39cb94b95bdbULL); }
  Pcg32(uint64_t state, uint64_t stream) { seed(state, stream); }

  void seed(uint64_t initState, uint64_t stream) {
    state_ = 0;
    increment_ = (stream << 1u) | 1u;
    nextUint();
    state_ += initState;
    nextUint();
  }

  uint32_t nextUint() {
    uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + increment_;
    uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
  }

  /// Uniform in [0, 1): 53 random bits, so 1.0 is never returned.
  double next() {
    uint64_t hi = nextUint(), lo = nextUint();
    return static_cast<double>(((hi << 32) | lo) >> 11) * 0x1.0p-53;
  }

 private:
  uint64_t state_ = 0, increment_ = 0;
};

/// SplitMix64 finaliser: mixes a 64-bit key into a well-spread seed.
inline uint64_t mixBits(uint64_t v) {
  v ^= v >> 30;
  v *= 0xbf58476d1ce4e5b9ULL;
  v ^= v >> 27;
  v *= 0x94d049bb133111ebULL;
  v ^= v >> 31;
  return v;
}

/// The generator for one camera sample of one pixel.
inline Pcg32 sampleGenerator(uint64_t seed, uint64_t pixelIndex, uint64_t sampleIndex) {
  return Pcg32(mixBits(seed * 0x9e3779b97f4a7c15ULL + sampleIndex), mixBits(pixelIndex ^ (seed << 32)));
}

}  // namespace radiant
