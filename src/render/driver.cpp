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
#include <filesystem>
#include <mutex>

#include "cluster/cluster.h"
#include "render/checkpoint.h"
#include "util/error.h"
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

/// Zeroes the pixels another rank owns (their values came from the last
/// round's sum), so that the sum over the ranks counts each pixel once.
void keepOwnPixels(Film &film, const std::vector<uint8_t> &own) {
  forEachFilmArray(
      film,
      [&](std::vector<Bands> &v) {
        for (size_t p = 0; p < v.size(); ++p)
          if (!own[p]) v[p] = Bands(0.0);
      },
      [&](std::vector<uint32_t> &v) {
        for (size_t p = 0; p < v.size(); ++p)
          if (!own[p]) v[p] = 0;
      });
}

/// The whole film on every rank (root only: on rank 0), from each rank's own pixels.
void sumFilmOverRanks(Film &film, const std::vector<uint8_t> &own, bool everyRank) {
  keepOwnPixels(film, own);
  forEachFilmArray(
      film,
      [&](std::vector<Bands> &v) {
        double *values = reinterpret_cast<double *>(v.data());
        everyRank ? cluster::sumOnAllRanks(values, v.size() * kBandCount)
                  : cluster::sumOnRoot(values, v.size() * kBandCount);
      },
      [&](std::vector<uint32_t> &v) {
        everyRank ? cluster::sumOnAllRanks(v.data(), v.size()) : cluster::sumOnRoot(v.data(), v.size());
      });
}

/// The driver for either film: `shade(pixel, ray, rng)` takes one camera
/// sample. `stopConverged`, when given, clears between rounds the flags of
/// the active pixels that may stop (from kMinimumSamples on).
template <typename Shade>
RenderStats drive(const PinholeCamera &camera, const DriverOptions &options, Film &film, const Shade &shade,
                  const ProgressCallback &progress,
                  const std::function<void(std::vector<uint8_t> &active)> &stopConverged = {}) {
  const auto start = Clock::now();
  const int width = film.width, height = film.height;
  std::vector<Tile> tiles;
  if (options.onlyPixelX >= 0) {
    tiles.push_back({options.onlyPixelX, options.onlyPixelY, options.onlyPixelX + 1, options.onlyPixelY + 1});
  } else {
    for (int y = 0; y < height; y += options.tileSize)
      for (int x = 0; x < width; x += options.tileSize)
        tiles.push_back({x, y, std::min(x + options.tileSize, width), std::min(y + options.tileSize, height)});
  }
  // This rank's tiles: every N-th, so that each rank has a share of every part of the image.
  const size_t ranks = size_t(cluster::size()), me = size_t(cluster::rank());
  std::vector<uint8_t> ownPixel;
  if (ranks > 1) {
    ownPixel.assign(size_t(width) * height, 0);
    for (size_t t = me; t < tiles.size(); t += ranks)
      for (int y = tiles[t].y0; y < tiles[t].y1; ++y)
        for (int x = tiles[t].x0; x < tiles[t].x1; ++x) ownPixel[size_t(y) * width + x] = 1;
  }

  const int target = options.samplesPerPixel;
  const double budget = options.timeBudgetSeconds;
  int done = 0;
  std::mutex progressMutex;
  auto lastReport = Clock::now() - std::chrono::seconds(1);
  double elapsedBefore = 0;  // in the run a checkpoint came from
  auto elapsedSeconds = [&] { return elapsedBefore + secondsSince(start); };

  auto report = [&](int samplesDone, double roundFraction, int roundSamples, bool force) {
    if (!progress) return;
    std::lock_guard lock(progressMutex);
    if (!force && secondsSince(lastReport) < 0.2) return;
    lastReport = Clock::now();
    Progress p;
    p.samplesDone = samplesDone;
    p.samplesTarget = target;
    p.timeBudgetSeconds = budget;
    p.elapsedSeconds = elapsedSeconds();
    double sampleFraction = (samplesDone + roundFraction * roundSamples) / target;
    p.fraction = budget > 0 ? std::max(sampleFraction, std::min(1.0, p.elapsedSeconds / budget)) : sampleFraction;
    p.fraction = force ? 1.0 : std::min(1.0, p.fraction);
    p.etaSeconds = p.fraction > 0 ? p.elapsedSeconds * (1 - p.fraction) / p.fraction : -1;
    progress(p);
  };

  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  const size_t pixels = options.onlyPixelX >= 0 ? 1 : size_t(width) * height;
  std::vector<uint8_t> active(size_t(width) * height, 1);
  std::vector<uint8_t> tileDone(tiles.size(), 0);  // in the round in progress
  size_t activeCount = pixels;
  uint64_t pixelSamples = 0;  // camera samples taken so far, over all pixels
  bool interrupted = false;
  RenderStats stats;

  // A checkpoint to carry on from: the film, the converged pixels, and the round it was in.
  const bool checkpointing = !options.checkpointPath.empty();
  int resumedRoundEnd = 0;
  if (checkpointing && options.resume && std::filesystem::exists(options.checkpointPath)) {
    RenderCheckpoint saved;
    readRenderCheckpoint(options.checkpointPath, options.checkpointJob, saved, film);
    if (saved.tileSize != options.tileSize || saved.tileDone.size() != tiles.size())
      throw InputError(InputLocation{options.checkpointPath},
                       "not a usable render checkpoint: its tiles are not this render's");
    done = saved.samplesDone;
    resumedRoundEnd = saved.roundEnd;
    tileDone = saved.tileDone;
    active = saved.active;
    elapsedBefore = saved.elapsedSeconds;
    pixelSamples = saved.cameraSamples;
    activeCount = options.onlyPixelX >= 0 ? 1 : size_t(std::count(active.begin(), active.end(), uint8_t(1)));
    stats.resumedFromSamples = done;
  }
  auto lastCheckpoint = Clock::now();
  // Collective with several ranks: each rank's complete tiles summed on rank 0, which writes.
  auto saveCheckpoint = [&](int roundEnd) {
    RenderCheckpoint state;
    state.job = options.checkpointJob;
    state.tileSize = options.tileSize;
    state.samplesDone = done;
    state.roundEnd = roundEnd;
    state.elapsedSeconds = elapsedSeconds();
    state.cameraSamples = pixelSamples;
    state.tileDone = tileDone;
    state.active = active;
    if (ranks > 1) {
      Film whole = film;
      sumFilmOverRanks(whole, ownPixel, false);
      // Other ranks' flags are 0 here: each tile is marked by its owner only.
      for (size_t t = 0; t < tiles.size(); ++t)
        if (t % ranks != me) state.tileDone[t] = 0;
      cluster::sumOnRoot(state.tileDone.data(), state.tileDone.size());
      if (cluster::isRoot()) writeRenderCheckpoint(options.checkpointPath, state, whole);
    } else {
      writeRenderCheckpoint(options.checkpointPath, state, film);
    }
    lastCheckpoint = Clock::now();
    ++stats.checkpointsWritten;
  };

  while (true) {
    // Rounds double in size so early images are quick and the per-round
    // overhead vanishes; under a time budget a round is cut to what the
    // measured speed says fits in the time left. A resumed round keeps the
    // size it was saved with.
    int roundSamples = 0;
    if (resumedRoundEnd > done) {
      roundSamples = resumedRoundEnd - done;
    } else if (done < target && activeCount > 0) {
      std::fill(tileDone.begin(), tileDone.end(), uint8_t(0));
      const double elapsed = elapsedSeconds();
      roundSamples = std::min(target - done, std::max(1, done));
      if (budget > 0 && done > 0) {
        if (elapsed >= budget) roundSamples = 0;
        const double perPixelSample = elapsed / double(std::max<uint64_t>(1, pixelSamples));
        const int fits = static_cast<int>((budget - elapsed) / (perPixelSample * double(activeCount)));
        roundSamples = std::min(roundSamples, std::max(0, fits));
      }
      // Ctrl-C and SIGTERM are heard between tiles (below), and a doubling
      // round of a slow method (reichert: thousands of samples a second)
      // held minutes of work in one tile. Without pixel stopping, whose
      // decisions fall at round ends and must not depend on the clock, a
      // round is cut so that a tile of it takes about kTileSeconds at the
      // speed measured so far. The image stays the same: each pixel's
      // samples, and the order they are summed in, do not depend on rounds.
      const bool cutByTime = !stopConverged && done > 0 && roundSamples > 1;
      if (cutByTime) {
        constexpr double kTileSeconds = 1.0;
        const double threadSecondsPerPixelSample = elapsed * double(std::max(1, arena.max_concurrency())) *
                                                   double(ranks) / double(std::max<uint64_t>(1, pixelSamples));
        const double tilePixels = double(options.tileSize) * options.tileSize;
        const double fits = kTileSeconds / (threadSecondsPerPixelSample * tilePixels);
        roundSamples = std::clamp(fits < double(roundSamples) ? int(fits) : roundSamples, 1, roundSamples);
      }
      // Rank 0's clock decides a budgeted or time-cut round, for every rank.
      if (budget > 0 || (cutByTime && ranks > 1))
        roundSamples = static_cast<int>(cluster::fromRoot(int64_t(roundSamples)));
    }
    resumedRoundEnd = 0;
    if (roundSamples <= 0) break;

    const int first = done, last = done + roundSamples;
    std::vector<size_t> pending;  // this rank's tiles of the round still to do
    size_t ownTiles = 0;
    for (size_t t = me; t < tiles.size(); t += ranks, ++ownTiles)
      if (!tileDone[t]) pending.push_back(t);
    std::atomic<size_t> ownTilesDone{ownTiles - pending.size()};
    // Checkpointing takes the tiles in waves, with a save possible between
    // two; otherwise one wave holds them all. Every rank has as many waves
    // (some maybe empty): the save is collective.
    const size_t waves = checkpointing ? std::clamp<size_t>(tiles.size() / (ranks * 16), 1, 32) : 1;
    for (size_t wave = 0; wave < waves && !interrupted; ++wave) {
      const size_t waveStart = pending.size() * wave / waves, waveEnd = pending.size() * (wave + 1) / waves;
      arena.execute([&] {
        tbb::parallel_for(
            tbb::blocked_range<size_t>(waveStart, waveEnd, 1), [&](const tbb::blocked_range<size_t> &range) {
              for (size_t i = range.begin(); i != range.end(); ++i) {
                // Ctrl-C (util/interrupt.h): the tiles in flight finish, the rest
                // of the round is skipped; each pixel's mean stays its own samples'.
                if (interruptRequested()) continue;
                const Tile &tile = tiles[pending[i]];
                for (int y = tile.y0; y < tile.y1; ++y)
                  for (int x = tile.x0; x < tile.x1; ++x) {
                    size_t pixel = size_t(y) * width + x;
                    if (!active[pixel]) continue;
                    const Sampler::PixelOffsets offsets = Sampler::pixelOffsets(options.seed, pixel);
                    for (int s = first; s < last; ++s) {
                      // The first two numbers place the sample in its pixel.
                      Sampler rng(offsets, options.seed, pixel, options.firstSample + uint64_t(s));
                      double jitterX = rng.next(), jitterY = rng.next();
                      shade(pixel, camera.generateRay(x + jitterX, y + jitterY), rng);
                    }
                  }
                tileDone[pending[i]] = 1;
                const size_t finished = ++ownTilesDone;
                report(first, double(finished) / double(std::max<size_t>(1, ownTiles)), roundSamples, false);
              }
            });
      });
      // Every rank learns of an interrupt on any (a node's SIGTERM) and stops at the same wave.
      interrupted = cluster::anyRank(interruptRequested());
      if (checkpointing) {
        const bool due = secondsSince(lastCheckpoint) >= options.checkpointIntervalSeconds;
        if (interrupted || cluster::fromRoot(int64_t(due ? 1 : 0)) != 0) saveCheckpoint(last);
      }
    }
    if (interrupted) {
      pixelSamples += uint64_t(double(activeCount) * roundSamples * double(ownTilesDone.load()) /
                               double(std::max<size_t>(1, ownTiles)));
      break;
    }
    done = last;
    pixelSamples += uint64_t(activeCount) * roundSamples;
    if (ranks > 1) sumFilmOverRanks(film, ownPixel, true);
    if (stopConverged && done >= kMinimumSamples && options.onlyPixelX < 0) {
      stopConverged(active);
      activeCount = size_t(std::count(active.begin(), active.end(), uint8_t(1)));
    }
  }
  // The image so far, whole on rank 0 (every rank: the film is the same on all).
  if (interrupted && ranks > 1) sumFilmOverRanks(film, ownPixel, true);
  if (checkpointing && options.checkpointWhenDone && !interrupted) saveCheckpoint(done);
  report(done, 0, 0, true);

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
      std::vector<Bands> means(film.pixelCount());
      for (size_t p = 0; p < film.pixelCount(); ++p) means[p] = film.mean(p);
      // An edge: a neighbour's mean differs by more than kEdgeContrast of
      // the brighter. A pixel a light's edge barely crosses may have had
      // none of its first samples on the light, and a zero variance says
      // nothing about what those samples missed; its bright neighbour does.
      auto onEdge = [&](size_t pixel) {
        const int x = int(pixel % size_t(film.width)), y = int(pixel / size_t(film.width));
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= film.width || ny >= film.height) continue;
            const Bands &a = means[pixel], &b = means[size_t(ny) * size_t(film.width) + size_t(nx)];
            for (int band = 0; band < kBandCount; ++band)
              if (std::abs(a[band] - b[band]) > kEdgeContrast * std::max(a[band], b[band]) + 0.1 * imageMean[band])
                return true;
          }
        return false;
      };
      for (size_t pixel = 0; pixel < active.size(); ++pixel) {
        if (!active[pixel]) continue;
        const Bands &mean = means[pixel], variance = film.varianceOfMean(pixel);
        bool converged = true;
        for (int b = 0; b < kBandCount; ++b) {
          const double tolerance = kPixelTolerance * (mean[b] + 0.1 * imageMean[b]);
          converged = converged && variance[b] <= tolerance * tolerance;
        }
        if (converged && !onEdge(pixel)) active[pixel] = 0;
      }
    };
  if (film.channels.empty())
    return drive(
        camera, options, film,
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
      camera, options, film,
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
