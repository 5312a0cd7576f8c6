#include "render/multipass.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "render/caustic_photons.h"
#include "render/film_image.h"

namespace radiant {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// Adds another film's samples (same size): the mean of all samples of both.
void accumulate(Film &into, const Film &from) {
  for (size_t p = 0; p < into.pixelCount(); ++p) {
    into.sum[p] += from.sum[p];
    into.sumSquares[p] += from.sumSquares[p];
    into.samples[p] += from.samples[p];
  }
}

/// Shots of the progressive solution before the preview: the first image
/// comes within a second on the Cornell box.
constexpr int kPreviewShots = 32;
/// Knaus & Zwicker (2011): r²_{i+1} = r²_i (i + α)/(i + 1) keeps the caustic
/// estimate consistent as passes accumulate; α = 2/3 as they recommend.
constexpr double kRadiusAlpha = 2.0 / 3.0;
/// Samples per pixel of passes 1–4 and of the first unbiased pass (the
/// preview's 4 average the random choices of glass in view).
constexpr int kPreviewSpp = 4, kHighFrequencySpp = 4, kLowFrequencySpp = 8, kFirstUnbiasedSpp = 16;
/// Samples per pixel that share one caustic map in the unbiased passes.
constexpr int kUnbiasedChunk = 16;

/// SplitMix64 of the seed and a stream: distinct runs never share numbers.
uint64_t hashSeed(uint64_t seed, uint64_t stream) {
  uint64_t z = seed * 0x9e3779b97f4a7c15ULL + stream + 0x632be59bd9b4e019ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

void renderMultipass(const RayTracer &tracer, const PinholeCamera &camera, int width, int height,
                     const MultipassOptions &options, const MultipassSolver &solve, const MultipassOutput &output,
                     const MultipassProgress &progress) {
  const Clock::time_point start = Clock::now();
  const bool budgeted = options.timeBudgetSeconds > 0;
  auto spent = [&] { return budgeted && secondsSince(start) >= options.timeBudgetSeconds; };

  // One pass (or a chunk of one): render `spp` samples with `renderer` into `film`.
  auto render = [&](MultipassPass &pass, const Renderer &renderer, int spp, Film &film, int chunk = 0) {
    DriverOptions driver;
    driver.samplesPerPixel = spp;
    // Each pass and chunk its own numbers, reproducibly, and no two (seed, pass) alike.
    driver.seed = hashSeed(options.seed, uint64_t(pass.index) << 32 | uint64_t(chunk));
    driver.threads = options.threads;
    const std::string label = fmt::format("multipass {} ({})", pass.index, pass.name);
    renderImage(camera, renderer, driver, film, progress ? progress(label) : ProgressCallback{});
  };
  auto finish = [&](MultipassPass &pass, const Film &film, Clock::time_point passStart) {
    pass.seconds = secondsSince(passStart);
    output(pass, meanImage(film), varianceImage(film));
  };

  // Pass 1: the radiosity preview, from an interrupted progressive solution.
  Clock::time_point passStart = Clock::now();
  MultipassPass pass{1, "radiosity preview", kPreviewSpp};
  {
    Solution preview = solve(kPreviewShots);
    RendererOptions o = options.renderer;
    o.solution = &preview;
    Film film(width, height);
    render(pass, *createRenderer("interpolate", tracer, o), pass.samplesPerPixel, film);
    finish(pass, film, passStart);
  }
  if (spent()) return;

  // The solution the later passes read: progressive, to its tolerance.
  passStart = Clock::now();
  const Solution solution = solve(0);
  double radius = options.photonRadius;
  int photonPass = 0;
  auto causticMap = [&](MultipassPass &p) {
    CausticPhotonMap map(tracer, options.photonsPerPass, hashSeed(options.seed, 0xCA05ULL << 48 | uint64_t(photonPass)),
                         radius);
    ++photonPass;  // Knaus & Zwicker's i, from 1: the radius of the next map
    radius = map.radius() * std::sqrt((photonPass + kRadiusAlpha) / (photonPass + 1.0));
    p.causticPhotons = map.stored(), p.photonRadius = map.radius();
    return map;
  };

  // Pass 2: high frequency — kok (direct light and the brightest reflectors
  // per pixel, the rest of the solution interpolated) with caustics.
  pass = {2, "high frequency", kHighFrequencySpp};
  {
    const CausticPhotonMap caustics = causticMap(pass);
    RendererOptions o = options.renderer;
    o.solution = &solution;
    o.caustics = &caustics;
    Film film(width, height);
    render(pass, *createRenderer("kok", tracer, o), pass.samplesPerPixel, film);
    finish(pass, film, passStart);
  }

  // Passes 3 and 4: low frequency — path tracing that reads the solution
  // after one, then two non-specular bounces.
  for (int depth = 1; depth <= 2 && !spent(); ++depth) {
    passStart = Clock::now();
    pass = {2 + depth, fmt::format("low frequency, solution after {} bounce{}", depth, depth > 1 ? "s" : ""),
            kLowFrequencySpp};
    const CausticPhotonMap caustics = causticMap(pass);
    RendererOptions o = options.renderer;
    o.solution = &solution;
    o.caustics = &caustics;
    o.readSolutionDepth = depth;
    Film film(width, height);
    render(pass, *createRenderer("path", tracer, o), pass.samplesPerPixel, film);
    finish(pass, film, passStart);
  }

  // Passes 5…: unbiased path tracing with caustics, accumulated, each pass
  // about as long as all before it (doubling), within the budget. Within a
  // pass every kUnbiasedChunk samples per pixel get a new caustic map with a
  // smaller radius, so that all maps weigh the same in the accumulated image,
  // as Knaus & Zwicker's convergence argument assumes (review).
  Film unbiased(width, height);
  int done = 0, spp = kFirstUnbiasedSpp;
  double secondsPerSpp = 0;
  for (int index = 5; !spent() && done < options.samplesPerPixel; ++index) {
    passStart = Clock::now();
    spp = std::min(spp, options.samplesPerPixel - done);
    if (budgeted && secondsPerSpp > 0) {
      // Fit the pass in what is left; a sliver of a pass (under 1/8 of the
      // samples so far) would cost a photon map for little: stop instead.
      const int fits = int((options.timeBudgetSeconds - secondsSince(start)) / secondsPerSpp);
      if (fits < std::max(1, done / 8)) break;
      spp = std::min(spp, fits);
      if (spp > kUnbiasedChunk) spp -= spp % kUnbiasedChunk;  // whole chunks, each with its map
    }
    pass = {index, "unbiased path tracing", 0, 0, true};
    for (int chunk = 0, left = spp; left > 0; ++chunk, left -= kUnbiasedChunk) {
      const CausticPhotonMap caustics = causticMap(pass);
      RendererOptions o = options.renderer;
      o.solution = nullptr;
      o.caustics = &caustics;
      Film film(width, height);
      render(pass, *createRenderer("path", tracer, o), std::min(left, kUnbiasedChunk), film, chunk);
      accumulate(unbiased, film);
    }
    done += spp;
    pass.samplesPerPixel = done;
    secondsPerSpp = secondsSince(passStart) / spp;
    finish(pass, unbiased, passStart);
    spp = done;  // the next pass doubles the samples so far
  }
}

std::unique_ptr<Renderer> createMultipassPlaceholder(const RayTracer &, const RendererOptions &) {
  throw std::logic_error("multipass is a sequence of passes: run it with renderMultipass");
}

}  // namespace radiant
