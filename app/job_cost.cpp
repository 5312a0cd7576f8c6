#include "job_cost.h"

#include <fmt/format.h>
#include <sys/resource.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "render/film.h"
#include "util/error.h"

namespace radiant {

namespace {

double pixelCount(const RenderJobSize &job) {
  return double(job.width) * double(job.height);
}

/// Camera samples of the whole job (the ceiling, under a --time budget).
double sampleCount(const RenderJobSize &job) {
  return pixelCount(job) * double(job.samplesPerPixel) * double(job.passes);
}

}  // namespace

double renderImageBytes(const RenderJobSize &job) {
  const double pixels = pixelCount(job);
  // The film's sums per pixel, then each pass's image and each output's converted copy as three floats a pixel.
  const double film = double(Film::bytesPerPixel(size_t(job.channels)));
  const double images = 3.0 * sizeof(float) * double(job.passes + job.outputs);
  return pixels * (film + images);
}

std::optional<double> availableMemoryBytes() {
  std::optional<double> available;
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line)) {
    std::istringstream in(line);
    std::string key;
    double kib = 0;
    if (in >> key >> kib && key == "MemAvailable:") available = kib * 1024;
  }
  // A limit set on the process (ulimit -v, a batch system's) allows less.
  for (int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    rlimit limit{};
    if (getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
      available = std::min(available.value_or(double(limit.rlim_cur)), double(limit.rlim_cur));
  }
  return available;
}

bool isLargeRenderJob(const RenderJobSize &job) {
  constexpr double kLargePixels = 16.0 * (1 << 20), kLargeBytes = 1e9, kLargeSamples = 1e10;
  return pixelCount(job) >= kLargePixels || renderImageBytes(job) >= kLargeBytes ||
         (!job.timeBudget && sampleCount(job) >= kLargeSamples);
}

void announceRenderTime(const RenderJobSize &job, const PilotRate &pilot, bool atMost, int ranks) {
  const double samples = sampleCount(job);
  const double seconds = samples / (pilot.samplesPerSecond * std::max(ranks, 1));
  const std::string time = seconds < 120         ? fmt::format("{:.0f} s", seconds)
                           : seconds < 7200      ? fmt::format("{:.0f} min", seconds / 60)
                           : seconds < 2 * 86400 ? fmt::format("{:.1f} h", seconds / 3600)
                                                 : fmt::format("{:.1f} days", seconds / 86400);
  fmt::print(stderr,
             "radiant: a pilot of {} samples ran at {:.3g} M samples/s{}: the {:.3g} samples take {}about {}{}\n",
             pilot.samples, pilot.samplesPerSecond * 1e-6, ranks > 1 ? fmt::format(" per rank ({} ranks)", ranks) : "",
             samples, atMost ? "at most " : "", time,
             atMost ? " (this method's pixels stop early where they have converged)" : "");
}

void announceRenderJob(const RenderJobSize &job, bool quiet) {
  const double bytes = renderImageBytes(job);
  const double pixels = pixelCount(job), samples = sampleCount(job);
  const std::optional<double> available = availableMemoryBytes();
  auto gb = [](double b) { return b >= 1e9 ? fmt::format("{:.1f} GB", b / 1e9) : fmt::format("{:.0f} MB", b / 1e6); };
  if (available && bytes > *available)
    throw InputError(
        InputLocation{"--width/--height"},
        fmt::format("a {}x{} image needs at least {} for its film and images{}, and only {} is available "
                    "to this process: render a smaller image, or on a machine with more memory",
                    job.width, job.height, gb(bytes),
                    job.passes > 1 ? fmt::format(" ({} spectral passes)", job.passes) : "", gb(*available)));
  if (quiet || !isLargeRenderJob(job)) return;
  const std::string traced = job.timeBudget
                                 ? "samples as the --time budget allows"
                                 : fmt::format("{:.3g} samples ({} per pixel{})", samples, job.samplesPerPixel,
                                               job.passes > 1 ? fmt::format(", {} passes", job.passes) : "");
  fmt::print(stderr, "radiant: a large job: {}x{} = {} pixels, {}; the film and images hold {}{}\n", job.width,
             job.height, pixels >= 1e6 ? fmt::format("{:.1f} M", pixels / 1e6) : fmt::format("{:.0f}", pixels), traced,
             gb(bytes), available ? fmt::format(" of the {} available", gb(*available)) : "");
}

}  // namespace radiant
