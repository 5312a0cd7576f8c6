#include "radiosity/calculation_grid.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "colour/spectrum.h"
#include "radiosity/backprojection.h"
#include "radiosity/solution_query.h"
#include "scene/spectral_scene.h"
#include "util/atomic_file.h"
#include "util/interrupt.h"
#include "util/random.h"
#include "util/sampling.h"

namespace radiant {

namespace {

/// Gather rays are drawn in batches of this many between checks of the error.
constexpr int kBatch = 256;
/// An emitter's shaft with more faces than this has its visibility sampled
/// (DirectIrradiance), as in shirley.
constexpr size_t kMaxExactOccluders = 32;

/// lux per W·m⁻² of each band of a pass: 683 × the band's luminance weight.
Bands luxPerWattOfPass(const Scene &scene, int pass) {
  if (!scene.spectral.enabled()) {
    return Bands(0.2126390, 0.7151687, 0.0721923) * kLuminousEfficacy;
  }
  BandColourMatching matching(scene.spectral.wavelengths);
  Bands weights(0.0);
  for (int b = 0; b < kBandCount; ++b) {
    const size_t w = size_t(pass) * kBandCount + size_t(b);
    // The last pass repeats the last wavelength in its unused bands: counted once.
    if (w < scene.spectral.wavelengths.size()) weights[b] = kLuminousEfficacy * matching.xyzWeight(int(w)).y;
  }
  return weights;
}

double dotBands(const Bands &a, const Bands &b) {
  double sum = 0;
  for (int k = 0; k < kBandCount; ++k) sum += a[k] * b[k];
  return sum;
}

/// One pass's contribution at one point.
struct PassEstimate {
  double directLux = 0, indirectLux = 0, varianceOfMean = 0;
  int samples = 0;
};

PassEstimate estimatePoint(const RayTracer &tracer, const Solution &solution, const DirectIrradiance &direct,
                           const Bands &luxPerWatt, const Vec3 &x, const Vec3 &n, Pcg32 rng,
                           const GridOptions &options) {
  PassEstimate out;
  if (!direct.empty()) out.directLux = dotBands(direct.irradiance(x, n), luxPerWatt);
  const Frame frame = Frame::fromNormal(n);
  double sum = 0, sumSquares = 0;
  int count = 0;
  const int maxSamples = std::max(options.maxSamples, 1);
  while (count < maxSamples) {
    const int batch = std::min(kBatch, maxSamples - count);
    for (int k = 0; k < batch; ++k) {
      const double u1 = rng.next(), u2 = rng.next();
      const Vec3 wi = frame.toWorld(sampleCosineHemisphere(u1, u2));
      double value = 0;  // lux: π L_r with the cosine-weighted density's cos θ/π cancelled
      Hit hit;
      SolutionPoint at;
      if (tracer.intersect(tracer.spawnRay(x, n, wi), hit) && locateHit(solution, hit, -wi, at))
        value = kPi * dotBands(reflectedRadiance(solution, at), luxPerWatt);
      sum += value;
      sumSquares += value * value;
    }
    count += batch;
    const double mean = sum / count;
    const double variance = std::max(0.0, sumSquares / count - mean * mean) * count / std::max(count - 1, 1);
    out.indirectLux = mean;
    out.varianceOfMean = variance / count;
    out.samples = count;
    const double total = out.directLux + mean;
    if (count >= options.minSamples && std::sqrt(out.varianceOfMean) <= options.targetRelativeError * total) break;
  }
  return out;
}

void summarise(GridIlluminance &g) {
  if (g.points.empty()) return;
  g.minimumLux = std::numeric_limits<double>::infinity();
  g.maximumLux = -std::numeric_limits<double>::infinity();
  double sum = 0;
  for (const GridPointIlluminance &p : g.points) {
    g.minimumLux = std::min(g.minimumLux, p.illuminanceLux);
    g.maximumLux = std::max(g.maximumLux, p.illuminanceLux);
    sum += p.illuminanceLux;
  }
  // Cells are equal parallelograms, so the plain mean is the area average.
  g.averageLux = sum / double(g.points.size());
}

/// CSV quoting (RFC 4180): names may hold commas or quotes.
std::string csvField(const std::string &s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

std::vector<GridIlluminance> computeGridIlluminance(Scene &scene, const RayTracer &tracer,
                                                    std::span<const Solution> passes, const GridOptions &options) {
  const int passCount = scene.spectral.enabled() ? scene.spectral.passCount() : 1;
  if (passes.size() != size_t(passCount))
    throw std::logic_error("computeGridIlluminance: one solution per spectral pass expected");
  std::vector<GridIlluminance> results(scene.grids.size());
  for (size_t g = 0; g < scene.grids.size(); ++g) {
    results[g].grid = scene.grids[g];
    results[g].points.resize(scene.grids[g].pointCount());
  }
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  for (int pass = 0; pass < passCount; ++pass) {
    // DirectIrradiance reads the materials at each query: the pass's emission.
    if (scene.spectral.enabled()) applySpectralPass(scene, pass);
    const DirectIrradiance direct(scene, tracer, kMaxExactOccluders);
    const Bands luxPerWatt = luxPerWattOfPass(scene, pass);
    for (size_t g = 0; g < results.size(); ++g) {
      GridIlluminance &result = results[g];
      const CalculationGrid &grid = result.grid;
      arena.execute([&] {
        tbb::parallel_for(size_t(0), result.points.size(), [&](size_t index) {
          if (interruptRequested()) return;
          const int i = int(index % size_t(grid.nu)), j = int(index / size_t(grid.nu));
          const Vec3 x = grid.point(i, j);
          // Its own stream per (seed, grid, point, pass): the same numbers whatever thread runs it.
          const Pcg32 rng = sampleGenerator(options.seed ^ (0x51ed27u * (g + 1)), index, uint64_t(pass));
          const PassEstimate e =
              estimatePoint(tracer, passes[size_t(pass)], direct, luxPerWatt, x, grid.normal, rng, options);
          GridPointIlluminance &p = result.points[index];
          p.position = x;
          p.directLux += e.directLux;
          p.indirectLux += e.indirectLux;
          // The passes draw independent numbers: their variances add.
          p.standardErrorLux = std::sqrt(p.standardErrorLux * p.standardErrorLux + e.varianceOfMean);
          p.samples += e.samples;
          p.illuminanceLux = p.directLux + p.indirectLux;
        });
      });
    }
    if (interruptRequested()) throw Interrupted();
  }
  for (GridIlluminance &g : results) summarise(g);
  return results;
}

void writeGridReport(const std::vector<GridIlluminance> &grids, double metresPerUnit, const std::string &path,
                     std::span<const PointLight> lights) {
  std::string csv = "grid,i,j,x,y,z,illuminance_lux,standard_error_lux,direct_lux,indirect_lux,samples\n";
  for (const GridIlluminance &g : grids) {
    const std::string name = csvField(g.grid.name);
    for (int j = 0; j < g.grid.nv; ++j)
      for (int i = 0; i < g.grid.nu; ++i) {
        const GridPointIlluminance &p = g.at(i, j);
        const Vec3 x = p.position / metresPerUnit;
        csv += fmt::format("{},{},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{}\n", name, i, j, x.x, x.y, x.z,
                           p.illuminanceLux, p.standardErrorLux, p.directLux, p.indirectLux, p.samples);
      }
  }
  for (const GridIlluminance &g : grids)
    csv += fmt::format("# grid {}: points {} E_min_lux {:.9g} E_avg_lux {:.9g} E_max_lux {:.9g} U0 {:.9g} Ud {:.9g}\n",
                       csvField(g.grid.name), g.points.size(), g.minimumLux, g.averageLux, g.maximumLux, g.uniformity(),
                       g.diversity());
  for (const PointLight &light : lights) csv += "# light " + describeLight(light) + "\n";
  writeAtomically(path, [&](const std::string &temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out << csv;
    out.close();
    if (!out) throw std::runtime_error("write failed");
  });
}

}  // namespace radiant
