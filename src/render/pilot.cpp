#include "render/pilot.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>

#include "render/sampler.h"

namespace radiant {

PilotRate measureSampleRate(const PinholeCamera &camera, const Renderer &renderer, int width, int height, int threads,
                            double seconds) {
  using Clock = std::chrono::steady_clock;
  constexpr int kLattice = 64;
  constexpr uint64_t kPilotSeed = 0x9e3779b97f4a7c15ULL;  // not an image's seed: its own numbers
  const int columns = std::min(kLattice, width), rows = std::min(kLattice, height);
  const size_t lattice = size_t(columns) * size_t(rows);
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  const auto start = Clock::now();
  const auto deadline = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  std::atomic<size_t> taken{0};
  // Rounds over the lattice, one sample per pixel each, until the deadline;
  // a slow method (seconds a sample) stops inside its first round.
  for (int round = 0; Clock::now() < deadline || taken.load() == 0; ++round) {
    arena.execute([&] {
      tbb::parallel_for(size_t(0), lattice, [&](size_t k) {
        if (taken.load(std::memory_order_relaxed) > 0 && Clock::now() >= deadline) return;
        // The lattice pixel's centre cell, a sample placed by the sampler's first two numbers.
        const int x = int((k % size_t(columns)) * size_t(width) / size_t(columns));
        const int y = int((k / size_t(columns)) * size_t(height) / size_t(rows));
        const size_t pixel = size_t(y) * size_t(width) + size_t(x);
        Sampler rng(kPilotSeed, pixel, uint64_t(round));
        const double jitterX = rng.next(), jitterY = rng.next();
        renderer.radiance(camera.generateRay(x + jitterX, y + jitterY), rng);
        taken.fetch_add(1, std::memory_order_relaxed);
      });
    });
  }
  PilotRate rate;
  rate.samples = taken.load();
  rate.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  rate.samplesPerSecond = double(rate.samples) / std::max(rate.seconds, 1e-9);
  return rate;
}

}  // namespace radiant
