#include "render/driver.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>

#include "util/interrupt.h"

namespace radiant {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct Tile {
  int x0, y0, x1, y1;
};

/// The driver for either film: `shade(pixel, ray, rng)` takes one camera
/// sample. `stopConverged`, when given, clears between rounds the flags of
/// the active pixels that may stop (from kMinimumSamples on).
template <typename Shade>
RenderStats drive(const PinholeCamera &camera, const DriverOptions &options, int width, int height, const Shade &shade,
                  const ProgressCallback &progress,
                  const std::function<void(std::vector<uint8_t> &active)> &stopConverged = {}) {
  const auto start = Clock::now();
  std::vector<Tile> tiles;
  if (options.onlyPixelX >= 0) {
    tiles.push_back({options.onlyPixelX, options.onlyPixelY, options.onlyPixelX + 1, options.onlyPixelY + 1});
  } else {
    for (int y = 0; y < height; y += options.tileSize)
      for (int x = 0; x < width; x += options.tileSize)
        tiles.push_back({x, y, std::min(x + options.tileSize, width), std::min(y + options.tileSize, height)});
  }

  const int target = options.samplesPerPixel;
  const double budget = options.timeBudgetSeconds;
  int done = 0;
  std::mutex progressMutex;
  auto lastReport = Clock::now() - std::chrono::seconds(1);

  auto report = [&](int samplesDone, double roundFraction, int roundSamples, bool force) {
    if (!progress) return;
    std::lock_guard lock(progressMutex);
    if (!force && secondsSince(lastReport) < 0.2) return;
    lastReport = Clock::now();
    Progress p;
    p.samplesDone = samplesDone;
    p.samplesTarget = target;
    p.timeBudgetSeconds = budget;
    p.elapsedSeconds = secondsSince(start);
    double sampleFraction = (samplesDone + roundFraction * roundSamples) / target;
    p.fraction = budget > 0 ? std::max(sampleFraction, std::min(1.0, p.elapsedSeconds / budget)) : sampleFraction;
    p.fraction = force ? 1.0 : std::min(1.0, p.fraction);
    p.etaSeconds = p.fraction > 0 ? p.elapsedSeconds * (1 - p.fraction) / p.fraction : -1;
    progress(p);
  };

  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  const size_t pixels = options.onlyPixelX >= 0 ? 1 : size_t(width) * height;
  std::vector<uint8_t> active(size_t(width) * height, 1);
  size_t activeCount = pixels;
  uint64_t pixelSamples = 0;  // camera samples taken so far, over all pixels
  bool interrupted = false;
  while (done < target && activeCount > 0) {
    double elapsed = secondsSince(start);
    if (budget > 0 && done > 0 && elapsed >= budget) break;
    // Rounds double in size so early images are quick and the per-round
    // overhead vanishes; under a time budget a round is cut to what the
    // measured speed says fits in the time left.
    int roundSamples = std::min(target - done, std::max(1, done));
    if (budget > 0 && done > 0) {
      double perPixelSample = elapsed / double(pixelSamples);
      int fits = static_cast<int>((budget - elapsed) / (perPixelSample * double(activeCount)));
      if (fits < 1) break;
      roundSamples = std::min(roundSamples, fits);
    }
    std::atomic<size_t> tilesDone{0};
    const int first = done, last = done + roundSamples;
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const tbb::blocked_range<size_t> &range) {
        for (size_t t = range.begin(); t != range.end(); ++t) {
          // Ctrl-C (util/interrupt.h): the tiles in flight finish, the rest
          // of the round is skipped; each pixel's mean stays its own samples'.
          if (interruptRequested()) continue;
          const Tile &tile = tiles[t];
          for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) {
              size_t pixel = size_t(y) * width + x;
              if (!active[pixel]) continue;
              const Sampler::PixelOffsets offsets = Sampler::pixelOffsets(options.seed, pixel);
              for (int s = first; s < last; ++s) {
                Sampler rng(offsets, options.seed, pixel, s);  // the first two numbers place the sample in its pixel
                double jitterX = rng.next(), jitterY = rng.next();
                shade(pixel, camera.generateRay(x + jitterX, y + jitterY), rng);
              }
            }
          size_t finished = ++tilesDone;
          report(first, double(finished) / tiles.size(), roundSamples, false);
        }
      });
    });
    if (interruptRequested()) {
      interrupted = true;
      pixelSamples += uint64_t(activeCount) * roundSamples * tilesDone / std::max<size_t>(1, tiles.size());
      break;
    }
    done = last;
    pixelSamples += uint64_t(activeCount) * roundSamples;
    if (stopConverged && done >= kMinimumSamples && options.onlyPixelX < 0) {
      stopConverged(active);
      activeCount = size_t(std::count(active.begin(), active.end(), uint8_t(1)));
    }
  }
  report(done, 0, 0, true);

  RenderStats stats;
  stats.samplesPerPixel = done;
  stats.seconds = secondsSince(start);
  stats.cameraSamples = pixelSamples;
  stats.interrupted = interrupted;
  return stats;
}

}  // namespace

RenderStats renderImage(const PinholeCamera &camera, const Renderer &renderer, const DriverOptions &options, Film &film,
                        const ProgressCallback &progress) {
  std::function<void(std::vector<uint8_t> &)> stopConverged;
  if (options.stopConvergedPixels && renderer.variesOnlyAcrossThePixel())
    stopConverged = [&](std::vector<uint8_t> &active) {
      // Against the image's mean of this round, so that dark pixels stop too.
      Bands imageMean(0.0);
      for (size_t p = 0; p < film.pixelCount(); ++p) imageMean += film.mean(p);
      imageMean = imageMean / double(std::max<size_t>(1, film.pixelCount()));
      for (size_t pixel = 0; pixel < active.size(); ++pixel) {
        if (!active[pixel]) continue;
        const Bands mean = film.mean(pixel), variance = film.varianceOfMean(pixel);
        bool converged = true;
        for (int b = 0; b < kBandCount; ++b) {
          const double tolerance = kPixelTolerance * (mean[b] + 0.1 * imageMean[b]);
          converged = converged && variance[b] <= tolerance * tolerance;
        }
        if (converged) active[pixel] = 0;
      }
    };
  if (film.channels.empty())
    return drive(
        camera, options, film.width, film.height,
        [&](size_t pixel, const Ray &ray, Sampler &rng) { film.add(pixel, renderer.radiance(ray, rng)); }, progress,
        stopConverged);
  // The film's channels, found among the renderer's by name.
  const std::vector<std::string> offered = renderer.channels();
  constexpr size_t kMaxChannels = 8;
  if (offered.size() > kMaxChannels || film.channels.size() > kMaxChannels)
    throw std::logic_error("more film channels than the driver holds");
  std::vector<size_t> source;
  for (const FilmChannel &c : film.channels) {
    auto it = std::find(offered.begin(), offered.end(), c.name);
    if (it == offered.end()) throw std::logic_error("the renderer gives no channel '" + c.name + "'");
    source.push_back(size_t(it - offered.begin()));
  }
  return drive(
      camera, options, film.width, film.height,
      [&](size_t pixel, const Ray &ray, Sampler &rng) {
        std::array<Bands, kMaxChannels> values, picked;
        const Bands L = renderer.sample(ray, rng, values.data());
        for (size_t c = 0; c < source.size(); ++c) picked[c] = values[source[c]];
        film.add(pixel, L, picked.data());
      },
      progress, stopConverged);
}

ProgressCallback makeConsoleProgress(const std::string &label) {
  bool terminal = isatty(fileno(stderr));
  auto lastLine = std::make_shared<Clock::time_point>(Clock::now());
  return [terminal, label, lastLine](const Progress &p) {
    std::string eta = p.etaSeconds >= 0 ? fmt::format("{:.1f}s", p.etaSeconds) : std::string("?");
    std::string samples = p.timeBudgetSeconds > 0
                              ? fmt::format("{} spp, budget {:g}s", p.samplesDone, p.timeBudgetSeconds)
                              : fmt::format("{}/{} spp", p.samplesDone, p.samplesTarget);
    if (terminal) {
      constexpr int kWidth = 30;
      int filled = static_cast<int>(p.fraction * kWidth + 0.5);
      fmt::print(stderr, "\r{} [{}{}] {:3.0f}%  {}  {:.1f}s  ETA {}   ", label, std::string(filled, '#'),
                 std::string(kWidth - filled, '.'), 100 * p.fraction, samples, p.elapsedSeconds, eta);
      if (p.fraction >= 1) fmt::print(stderr, "\n");
    } else if (secondsSince(*lastLine) >= 5 || p.fraction >= 1) {
      *lastLine = Clock::now();
      fmt::print(stderr, "{}: {:.0f}% ({}, {:.1f}s elapsed, ETA {})\n", label, 100 * p.fraction, samples,
                 p.elapsedSeconds, eta);
    }
  };
}

}  // namespace radiant
