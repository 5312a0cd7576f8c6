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

double renderImageBytes(const RenderJobSize &job) {
  const double pixels = double(job.width) * double(job.height);
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

void announceRenderJob(const RenderJobSize &job, bool quiet) {
  const double bytes = renderImageBytes(job);
  const double pixels = double(job.width) * double(job.height);
  const double samples = pixels * double(job.samplesPerPixel) * double(job.passes);
  const std::optional<double> available = availableMemoryBytes();
  auto gb = [](double b) { return b >= 1e9 ? fmt::format("{:.1f} GB", b / 1e9) : fmt::format("{:.0f} MB", b / 1e6); };
  if (available && bytes > *available)
    throw InputError(
        InputLocation{"--width/--height"},
        fmt::format("a {}x{} image needs at least {} for its film and images{}, and only {} is available "
                    "to this process: render a smaller image, or on a machine with more memory",
                    job.width, job.height, gb(bytes),
                    job.passes > 1 ? fmt::format(" ({} spectral passes)", job.passes) : "", gb(*available)));
  constexpr double kLargePixels = 16.0 * (1 << 20), kLargeBytes = 1e9, kLargeSamples = 1e10;
  if (quiet || (pixels < kLargePixels && bytes < kLargeBytes && (job.timeBudget || samples < kLargeSamples))) return;
  const std::string traced = job.timeBudget
                                 ? "samples as the --time budget allows"
                                 : fmt::format("{:.3g} samples ({} per pixel{})", samples, job.samplesPerPixel,
                                               job.passes > 1 ? fmt::format(", {} passes", job.passes) : "");
  fmt::print(stderr,
             "radiant: a large job: {}x{} = {} pixels, {}; the film and images hold {}{}; the "
             "progress line gives the time left once the first tiles are done\n",
             job.width, job.height,
             pixels >= 1e6 ? fmt::format("{:.1f} M", pixels / 1e6) : fmt::format("{:.0f}", pixels), traced, gb(bytes),
             available ? fmt::format(" of the {} available", gb(*available)) : "");
}

}  // namespace radiant
