// radiosity_accuracy — the radiosity pipelines against a converged path-traced
// reference of the Cornell box, at equal wall time, beside RenderPark.
//
// The question: how close does Radiant's radiosity image get to the converged
// image, for a given wall time of solve + render together, and how does that
// compare with RenderPark's hierarchical Galerkin radiosity at the same time?
// At 256x256 on --threads (default 2), for each budget (--budgets, default
// 0.25,0.5,1,2,5,10,30 s) and pipeline, --repeats times (default 3, seeds 1..N
// for both the solve and the render):
//
//   default     exactly what `radiant render scenes/cornell-box/scene.json
//               --method interpolate` does with no flags: MeshOptions{} and
//               SolverOptions{} ("auto"), seed = the repeat, the `interpolate`
//               renderer with the command line's RenderContext. --solver,
//               --set and --mesh-size do not touch it: it is the baseline;
//   METHOD[:Q]  each of --methods (default interpolate,shirley): the scene
//               meshed and solved with SolverOptions{} changed by --solver,
//               --set key=value and --mesh-size (none given: the same solve
//               as `default`), then createRenderer(METHOD) on that solution;
//               with :Q (draft, low, normal, high, best) the solve takes that
//               --quality preset (radiosity/solver.h qualityLevels).
//
// Each run: meshAndSolve() and createRenderer() timed together ("solve s"),
// then renderImage() with timeBudgetSeconds = budget − solve s (at least one
// sample per pixel: a solve that uses up the budget gets exactly 1 spp, and
// such a row is marked "*" when it overruns the budget by more than 10 %).
//
// One untimed solve and 1-spp render of `default` comes first, so that the
// first timed run does not pay for starting the thread pools.
//
// The metric (the one the project measured RenderPark with):
//   - only the pixels whose reference has every channel ≤ 1 W·sr⁻¹·m⁻² (not
//     the light);
//   - per channel, mean test / mean reference over those pixels;
//   - RMSE over those pixels and the three channels with the reference's
//     noise removed, √max(0, MSE − mean variance of the reference's pixel
//     means over the same pixels);
//   - per object: each included pixel belongs to the object its centre ray
//     (generateRay(x + 0.5, y + 0.5)) hits; Σ test / Σ reference over its
//     pixels and the three channels. Printed per pipeline at its largest budget.
// The table holds the medians of the repeats.
//
// The reference is a `path` image of --reference-spp (default 32768) samples,
// seed 1000003 (not one of the test seeds), read from --reference (default
// build/cornell-reference-256-32k.exr) and --reference-variance (default the
// .var.exr beside it); rendered and written there only when either is missing.
// The load average is printed before and after (docs/PERFORMANCE.md: the
// machine is shared).
//
// Usage: radiosity_accuracy [scene.json] [--budgets 0.25,0.5,1,2,5,10,30] [--repeats 3] [--threads 2]
//          [--methods interpolate,shirley] [--solver NAME] [--set key=value]... [--mesh-size METRES]
//          [--reference FILE.exr] [--reference-variance FILE.exr] [--reference-spp 32768] [--csv FILE]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "bench_common.h"
#include "io/image.h"
#include "mesh/mesh.h"
#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"
#include "render/driver.h"
#include "render/film_image.h"
#include "render/registry.h"
#include "render/renderer.h"
#include "scene/camera.h"
#include "scene/load_scene.h"
#include "util/error.h"

using namespace radiant;
using radiant::bench::median;
using radiant::bench::secondsSince;
using radiant::bench::variancePathFor;

namespace {

constexpr int kSize = 256;                    // pixels, both sides
constexpr uint64_t kReferenceSeed = 1000003;  // not one of the test seeds 1..repeats
constexpr double kLightThreshold = 1.0;  // W·sr⁻¹·m⁻²: a reference pixel above this in any channel is the light

// RenderPark (rpkCpp at 37e5ff4e, hierarchical Galerkin, one thread, solution
// ray cast at 1024² box-filtered to 256²), measured by the project on the
// same metric: wall time of solve + display, and the RMSE.
struct RenderParkRow {
  double seconds, rmse;
};
constexpr RenderParkRow kRenderPark[] = {
    {0.21, 0.00793}, {0.27, 0.00404}, {0.58, 0.00242}, {2.07, 0.00195}, {7.85, 0.00180}, {35.1, 0.00174},
};
// Its mean ratios test / reference per channel (R, G, B) at 0.58 s.
constexpr double kRenderParkMeanRatios[3] = {0.994, 0.996, 0.997};

/// RenderPark's RMSE at a budget: the best among its rows that took at most
/// that long; NAN when none did.
double renderParkRmse(double budget) {
  double best = NAN;
  for (const RenderParkRow &row : kRenderPark)
    if (row.seconds <= budget && !(row.rmse >= best)) best = row.rmse;
  return best;
}

// --set key=value: the SolverOptions fields by name.
using SolverField =
    std::variant<std::string SolverOptions::*, double SolverOptions::*, int SolverOptions::*, size_t SolverOptions::*>;
const std::map<std::string, SolverField> &solverFields() {
  static const std::map<std::string, SolverField> fields = {
      {"solver", &SolverOptions::solver},
      {"tolerance", &SolverOptions::tolerance},
      {"maxIterations", &SolverOptions::maxIterations},
      {"visibilitySamples", &SolverOptions::visibilitySamples},
      {"formFactor", &SolverOptions::formFactor},
      {"hemicubeResolution", &SolverOptions::hemicubeResolution},
      {"linkThreshold", &SolverOptions::linkThreshold},
      {"minimumArea", &SolverOptions::minimumArea},
      {"raysPerElement", &SolverOptions::raysPerElement},
      {"refinementRounds", &SolverOptions::refinementRounds},
      {"directTolerance", &SolverOptions::directTolerance},
      {"directMinimumEdge", &SolverOptions::directMinimumEdge},
      {"linkError", &SolverOptions::linkError},
      {"linkMinimumEdge", &SolverOptions::linkMinimumEdge},
      {"maxElements", &SolverOptions::maxElements},
      {"adaptiveRounds", &SolverOptions::adaptiveRounds},
      {"adaptiveThreshold", &SolverOptions::adaptiveThreshold},
  };
  return fields;
}

/// Applies "key=value" to `options`; false (with a message) for an unknown key or a bad value. Every
/// numeric field here is a count, a tolerance or a length, so a negative value is refused too; what
/// else a value must satisfy the solver checks.
bool applySetting(const std::string &setting, SolverOptions &options) {
  const size_t equals = setting.find('=');
  const std::string key = setting.substr(0, equals),
                    value = equals == std::string::npos ? "" : setting.substr(equals + 1);
  auto found = solverFields().find(key);
  if (equals == std::string::npos || value.empty() || found == solverFields().end()) {
    std::string known;
    for (const auto &entry : solverFields()) known += (known.empty() ? "" : ", ") + entry.first;
    std::fprintf(stderr, "radiosity_accuracy: --set %s: expected key=value with key one of: %s\n", setting.c_str(),
                 known.c_str());
    return false;
  }
  char *end = nullptr;
  bool ok = true;
  std::visit(
      [&](auto member) {
        using T = std::remove_reference_t<decltype(options.*member)>;
        if constexpr (std::is_same_v<T, std::string>) {
          options.*member = value;
        } else if constexpr (std::is_same_v<T, double>) {
          double v = std::strtod(value.c_str(), &end);
          ok = *end == 0 && std::isfinite(v) && v >= 0;
          if (ok) options.*member = v;
        } else {
          long long v = std::strtoll(value.c_str(), &end, 10);
          ok = *end == 0 && v >= 0;
          if (ok) options.*member = T(v);
        }
      },
      found->second);
  if (!ok)
    std::fprintf(stderr, "radiosity_accuracy: --set %s: '%s' is not a valid value (a number ≥ 0)\n", key.c_str(),
                 value.c_str());
  return ok;
}

/// An InputError location that is a flag or a file, not a place inside one.
InputLocation where(const std::string &flagOrFile) {
  InputLocation location;
  location.file = flagOrFile;
  return location;
}

/// The pixels measured, each with the object its centre ray hits.
struct Mask {
  std::vector<size_t> pixels;    ///< indices y·width + x of the included pixels
  std::vector<int> pixelObject;  ///< per included pixel: index into names, −1 for none
  std::vector<std::string> names;
  double referenceNoise = 0;  ///< mean variance of the reference pixel means over them and the channels
};

struct Measurement {
  double solveSeconds = 0, totalSeconds = 0, spp = 0, rmse = 0;
  double meanRatio[3] = {0, 0, 0};
  std::vector<double> objectRatio;  ///< per Mask::names entry (NAN where no pixel)
  std::vector<size_t> objectPixels;
  size_t nonFinitePixels = 0;
};

/// The metric of the header on `test` against `reference`.
void measure(const Image &test, const Image &reference, const Mask &mask, Measurement &m) {
  double sumTest[3] = {0, 0, 0}, sumReference[3] = {0, 0, 0}, squared = 0;
  size_t counted = 0;
  std::vector<double> objectTest(mask.names.size(), 0), objectReference(mask.names.size(), 0);
  m.objectPixels.assign(mask.names.size(), 0);
  m.nonFinitePixels = 0;
  for (size_t i = 0; i < mask.pixels.size(); ++i) {
    const float *t = &test.rgb[mask.pixels[i] * 3], *r = &reference.rgb[mask.pixels[i] * 3];
    if (!std::isfinite(t[0]) || !std::isfinite(t[1]) || !std::isfinite(t[2])) {
      ++m.nonFinitePixels;
      continue;
    }
    ++counted;
    const int object = mask.pixelObject[i];
    if (object >= 0) ++m.objectPixels[object];
    for (int c = 0; c < 3; ++c) {
      sumTest[c] += t[c];
      sumReference[c] += r[c];
      squared += (double(t[c]) - r[c]) * (double(t[c]) - r[c]);
      if (object >= 0) {
        objectTest[object] += t[c];
        objectReference[object] += r[c];
      }
    }
  }
  for (int c = 0; c < 3; ++c) m.meanRatio[c] = sumReference[c] > 0 ? sumTest[c] / sumReference[c] : NAN;
  const double mse = counted ? squared / (3.0 * double(counted)) : NAN;
  m.rmse = std::sqrt(std::max(0.0, mse - mask.referenceNoise));
  m.objectRatio.assign(mask.names.size(), NAN);
  for (size_t o = 0; o < mask.names.size(); ++o)
    if (objectReference[o] > 0) m.objectRatio[o] = objectTest[o] / objectReference[o];
}

struct Pipeline {
  std::string name;       ///< "default" or a method
  std::string renderer;   ///< the method rendered
  bool pristine = false;  ///< default: SolverOptions{} and MeshOptions{}, nothing from the command line
  std::string quality;    ///< METHOD:QUALITY: hierarchical-exact's --quality preset for its solve
};

struct Row {
  double budget = 0;
  std::string pipeline;
  Measurement median;
  size_t nonFinitePixels = 0;  // over all repeats
  bool overBudget = false;
  std::string solvedWith;  // what the solve ran, and its elements
  size_t elements = 0;
};

}  // namespace

int main(int argc, char **argv) {
  std::string scenePath = "scenes/cornell-box/scene.json", referencePath = "build/cornell-reference-256-32k.exr";
  std::string referenceVariancePath, csvPath, budgetList = "0.25,0.5,1,2,5,10,30", methodList = "interpolate,shirley";
  int referenceSpp = 32768, threads = 2, repeats = 3;
  double meshSizeMetres = 0;  // 0: MeshOptions' default, as `radiant` without --mesh-size
  SolverOptions configured;   // the methods' solve: SolverOptions{} changed by --solver and --set
  std::vector<std::string> settings;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    bool hasValue = i + 1 < argc;
    if (arg == "--reference" && hasValue)
      referencePath = argv[++i];
    else if (arg == "--reference-variance" && hasValue)
      referenceVariancePath = argv[++i];
    else if (arg == "--reference-spp" && hasValue)
      referenceSpp = std::atoi(argv[++i]);
    else if (arg == "--budgets" && hasValue)
      budgetList = argv[++i];
    else if (arg == "--solver" && hasValue)
      configured.solver = argv[++i];
    else if (arg == "--set" && hasValue) {
      settings.push_back(argv[++i]);
      if (!applySetting(settings.back(), configured)) return 2;
    } else if (arg == "--methods" && hasValue)
      methodList = argv[++i];
    else if (arg == "--mesh-size" && hasValue)
      meshSizeMetres = std::atof(argv[++i]);
    else if (arg == "--threads" && hasValue)
      threads = std::atoi(argv[++i]);
    else if (arg == "--repeats" && hasValue)
      repeats = std::atoi(argv[++i]);
    else if (arg == "--csv" && hasValue)
      csvPath = argv[++i];
    else if (arg.rfind("--", 0) != 0)
      scenePath = arg;
    else {
      std::fprintf(stderr,
                   "usage: %s [scene.json] [--budgets 0.25,0.5,1,2,5,10,30] [--repeats 3] [--threads 2] "
                   "[--methods interpolate,shirley] [--solver NAME] [--set key=value]... [--mesh-size METRES] "
                   "[--reference FILE.exr] [--reference-variance FILE.exr] [--reference-spp 32768] [--csv FILE]\n",
                   argv[0]);
      return 2;
    }
  }
  if (referenceVariancePath.empty()) referenceVariancePath = variancePathFor(referencePath);
  std::vector<Pipeline> pipelines = {{"default", "interpolate", true}};
  std::istringstream methodStream(methodList);
  // METHOD or METHOD:QUALITY (a --quality preset of hierarchical-exact, radiosity/solver.h).
  for (std::string item; std::getline(methodStream, item, ',');) {
    if (item.empty()) continue;
    const size_t colon = item.find(':');
    Pipeline p{item, item.substr(0, colon), false};
    if (colon != std::string::npos) p.quality = item.substr(colon + 1);
    pipelines.push_back(p);
  }
  std::vector<double> budgets;
  std::istringstream budgetStream(budgetList);
  for (std::string item; std::getline(budgetStream, item, ',');) budgets.push_back(std::atof(item.c_str()));
  if (budgets.empty() || repeats < 1 || referenceSpp < 1 || threads < 0 || meshSizeMetres < 0 ||
      std::any_of(budgets.begin(), budgets.end(), [](double b) { return !(b > 0); })) {
    std::fprintf(stderr, "radiosity_accuracy: budgets must be positive, repeats and reference spp at least 1\n");
    return 2;
  }

  try {
    for (const Pipeline &p : pipelines) {
      if (p.renderer == "multipass")
        throw InputError(where("--methods"), "multipass runs its own passes: measure it with two_pass_equal_time");
      (void)findRenderer(p.renderer);  // an unknown name fails here, before any work
    }
    const double loadBefore = bench::loadAverage();
    Scene scene = loadScene(scenePath);
    RayTracer tracer(scene);
    PinholeCamera camera(scene.camera, kSize, kSize);
    // What `radiant render --method interpolate` passes its renderer (app/render_command.cpp): the scene's
    // texture filter of a time budget (its sample count is then the largest allowed).
    RenderContext baseOptions;
    baseOptions.pixelSpreadAngle = texturePixelSpread(scene.camera, kSize, kMaxSamplesPerPixel);

    // The reference: rendered once, then read from its files.
    Image reference, referenceVariance;
    if (std::filesystem::exists(referencePath) && std::filesystem::exists(referenceVariancePath)) {
      reference = readImage(referencePath);
      referenceVariance = readImage(referenceVariancePath);
      std::fprintf(stderr, "reference: read %s and %s\n", referencePath.c_str(), referenceVariancePath.c_str());
    } else {
      std::fprintf(stderr, "reference: rendering %d spp of path at %dx%d on %d threads\n", referenceSpp, kSize, kSize,
                   threads);
      auto renderer = createRenderer("path", tracer, baseOptions);
      DriverOptions driver;
      driver.samplesPerPixel = referenceSpp;
      driver.seed = kReferenceSeed;
      driver.threads = threads;
      Film film(kSize, kSize);
      RenderStats stats = renderImage(camera, *renderer, driver, film, makeConsoleProgress("reference"));
      reference = meanImage(film);
      referenceVariance = varianceImage(film);
      for (const std::string &path : {referencePath, referenceVariancePath})
        if (std::filesystem::path(path).has_parent_path())
          std::filesystem::create_directories(std::filesystem::path(path).parent_path());
      writeImage(reference, referencePath);
      writeImage(referenceVariance, referenceVariancePath);
      std::fprintf(stderr, "reference: %d spp in %.1f s, wrote %s and %s\n", stats.samplesPerPixel, stats.seconds,
                   referencePath.c_str(), referenceVariancePath.c_str());
      std::printf("reference rendered: %d spp of path in %.1f s on %d threads\n", stats.samplesPerPixel, stats.seconds,
                  threads);
    }
    if (reference.width != kSize || reference.height != kSize || referenceVariance.width != kSize ||
        referenceVariance.height != kSize)
      throw InputError(where(referencePath), "the reference and its variance must be 256x256");

    // The pixels measured, and the object each one's centre ray hits.
    Mask mask;
    std::vector<int> sceneObjectOf;  // per included pixel: Scene::objects index, −1 for none
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const size_t i = size_t(y) * kSize + x;
        const float *r = &reference.rgb[i * 3];
        if (!(r[0] <= kLightThreshold && r[1] <= kLightThreshold && r[2] <= kLightThreshold)) continue;
        mask.pixels.push_back(i);
        Hit hit;
        sceneObjectOf.push_back(
            tracer.intersect(camera.generateRay(x + 0.5, y + 0.5), hit) ? int(scene.faces[hit.face].object) : -1);
        for (int c = 0; c < 3; ++c) mask.referenceNoise += referenceVariance.rgb[i * 3 + c];
      }
    std::map<int, int> objectIndex;  // Scene::objects index → Mask::names index, in scene order
    for (int o : sceneObjectOf)
      if (o >= 0) objectIndex.emplace(o, 0);
    for (auto &[sceneObject, index] : objectIndex) {
      index = int(mask.names.size());
      mask.names.push_back(scene.objects[sceneObject].name);
    }
    for (int o : sceneObjectOf) mask.pixelObject.push_back(o >= 0 ? objectIndex[o] : -1);
    if (mask.pixels.empty()) throw InputError(where(referencePath), "no reference pixel is at most 1 in every channel");
    mask.referenceNoise /= 3.0 * double(mask.pixels.size());
    std::fprintf(stderr, "measuring %zu of %d pixels (reference ≤ %g W·sr⁻¹·m⁻² in every channel)\n",
                 mask.pixels.size(), kSize * kSize, kLightThreshold);

    MeshOptions configuredMesh;
    configuredMesh.maxEdgeLength = meshSizeMetres;
    configuredMesh.maxElements = configured.maxElements;  // as app/radiosity_options.cpp's solveScene

    {  // Untimed warm-up (thread pools, page faults, caches), so that the first timed run is not the slow one.
      SolverOptions solverOptions;
      solverOptions.threads = threads;
      Solution solution = meshAndSolve(scene, tracer, MeshOptions{}, solverOptions);
      RenderContext options = baseOptions;
      options.solution = &solution;
      DriverOptions driver;
      driver.samplesPerPixel = 1;
      driver.threads = threads;
      Film film(kSize, kSize);
      renderImage(camera, *createRenderer("interpolate", tracer, options), driver, film);
    }

    std::vector<Row> rows;
    for (double budget : budgets)
      for (const Pipeline &pipeline : pipelines) {
        const bool needsSolution = findRenderer(pipeline.renderer).needsSolution;
        std::vector<Measurement> runs;
        Row row;
        row.budget = budget;
        row.pipeline = pipeline.name;
        for (int repeat = 1; repeat <= repeats; ++repeat) {
          Measurement m;
          const auto start = std::chrono::steady_clock::now();
          Solution solution;
          RenderContext options = baseOptions;
          if (needsSolution) {
            SolverOptions solverOptions = pipeline.pristine ? SolverOptions{} : configured;
            if (!pipeline.quality.empty()) applyQuality(solverOptions, pipeline.quality);
            solverOptions.seed = uint64_t(repeat);
            solverOptions.threads = threads;
            solution = meshAndSolve(scene, tracer, pipeline.pristine ? MeshOptions{} : configuredMesh, solverOptions);
            options.solution = &solution;
            row.solvedWith = solution.stats.solver;
            row.elements = solution.elementCount();
          }
          auto renderer = createRenderer(pipeline.renderer, tracer, options);
          m.solveSeconds = secondsSince(start);
          DriverOptions driver;
          driver.samplesPerPixel = kMaxSamplesPerPixel;
          driver.seed = uint64_t(repeat);
          driver.threads = threads;
          // The driver takes 0 as "no budget": a solve that used the whole budget gets exactly 1 spp.
          if (budget > m.solveSeconds)
            driver.timeBudgetSeconds = budget - m.solveSeconds;
          else
            driver.samplesPerPixel = 1;
          Film film(kSize, kSize);
          RenderStats stats = renderImage(camera, *renderer, driver, film);
          m.totalSeconds = secondsSince(start);
          m.spp = stats.samplesPerPixel;
          measure(meanImage(film), reference, mask, m);
          std::fprintf(stderr,
                       "[%gs] %-11s %d/%d: solve %.3f s (%s, %zu elements), %d spp, total %.2f s, RMSE %.4g, "
                       "mean ratios %.4f %.4f %.4f%s\n",
                       budget, pipeline.name.c_str(), repeat, repeats, m.solveSeconds, row.solvedWith.c_str(),
                       row.elements, stats.samplesPerPixel, m.totalSeconds, m.rmse, m.meanRatio[0], m.meanRatio[1],
                       m.meanRatio[2], m.nonFinitePixels ? " (NON-FINITE PIXELS)" : "");
          runs.push_back(m);
        }
        auto medianOf = [&](auto field) {
          std::vector<double> values;
          for (const Measurement &m : runs) values.push_back(field(m));
          return median(values);
        };
        Measurement &med = row.median;
        med.solveSeconds = medianOf([](const Measurement &m) { return m.solveSeconds; });
        med.totalSeconds = medianOf([](const Measurement &m) { return m.totalSeconds; });
        med.spp = medianOf([](const Measurement &m) { return m.spp; });
        med.rmse = medianOf([](const Measurement &m) { return m.rmse; });
        for (int c = 0; c < 3; ++c) med.meanRatio[c] = medianOf([c](const Measurement &m) { return m.meanRatio[c]; });
        med.objectPixels = runs.front().objectPixels;
        for (size_t o = 0; o < mask.names.size(); ++o)
          med.objectRatio.push_back(medianOf([o](const Measurement &m) { return m.objectRatio[o]; }));
        for (const Measurement &m : runs) row.nonFinitePixels += m.nonFinitePixels;
        // The driver's last round is sized from the measured speed, so a few % over is normal; more is the 1-spp floor.
        row.overBudget = med.totalSeconds > 1.1 * budget;
        rows.push_back(row);
      }

    std::string configuredText = "solver '" + configured.solver + "'";
    for (const std::string &s : settings) configuredText += ", " + s;
    configuredText += meshSizeMetres > 0 ? ", mesh size " + std::to_string(meshSizeMetres) + " m"
                                         : ", mesh size default (1/8 of the largest side)";
    std::printf("\nradiosity_accuracy: %s at %dx%d, %d threads, median of %d repeats\n", scenePath.c_str(), kSize,
                kSize, threads, repeats);
    std::printf(
        "pipelines: default = `radiant render --method interpolate` with no flags (SolverOptions{}, "
        "MeshOptions{});");
    for (size_t p = 1; p < pipelines.size(); ++p) std::printf(" %s", pipelines[p].name.c_str());
    std::printf(" = %s\n", configuredText.c_str());
    for (const Pipeline &pipeline : pipelines)
      for (const Row &row : rows)
        if (row.pipeline == pipeline.name && !row.solvedWith.empty()) {
          std::printf("  %s: the solve ran %s, %zu elements\n", pipeline.name.c_str(), row.solvedWith.c_str(),
                      row.elements);
          break;
        }
    std::printf(
        "reference: %s (variance %s); %zu of %d pixels measured (every channel ≤ %g W·sr⁻¹·m⁻²); noise "
        "removed: mean variance of its pixel means %.3g (RMSE floor %.3g)\n\n",
        referencePath.c_str(), referenceVariancePath.c_str(), mask.pixels.size(), kSize * kSize, kLightThreshold,
        mask.referenceNoise, std::sqrt(mask.referenceNoise));
    std::printf(
        "| budget s | pipeline | solve s | total s | spp | mean R | mean G | mean B | RMSE | RenderPark RMSE | "
        "ours / RenderPark |\n");
    std::printf("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    FILE *csv = csvPath.empty() ? nullptr : std::fopen(csvPath.c_str(), "w");
    if (!csvPath.empty() && !csv) throw InputError(where(csvPath), "cannot open for writing");
    if (csv)
      std::fprintf(csv,
                   "budget_s,pipeline,solver,elements,solve_s,total_s,spp,mean_ratio_r,mean_ratio_g,mean_ratio_b,"
                   "rmse,renderpark_rmse,rmse_over_renderpark,over_budget,non_finite_pixels\n");
    for (const Row &row : rows) {
      const Measurement &m = row.median;
      const double rp = renderParkRmse(row.budget), ratio = std::isnan(rp) ? NAN : m.rmse / rp;
      char rpText[32] = "—", ratioText[32] = "—";
      if (!std::isnan(rp)) {
        std::snprintf(rpText, sizeof rpText, "%.4g", rp);
        std::snprintf(ratioText, sizeof ratioText, "%.2f", ratio);
      }
      std::printf("| %g | %s%s | %.3f | %.2f | %g | %.4f | %.4f | %.4f | %.4g | %s | %s |%s\n", row.budget,
                  row.pipeline.c_str(), row.overBudget ? " *" : "", m.solveSeconds, m.totalSeconds, m.spp,
                  m.meanRatio[0], m.meanRatio[1], m.meanRatio[2], m.rmse, rpText, ratioText,
                  row.nonFinitePixels ? "  NON-FINITE PIXELS" : "");
      if (csv)
        std::fprintf(csv, "%g,%s,%s,%zu,%.4f,%.4f,%g,%.6f,%.6f,%.6f,%.6g,%.6g,%.4f,%d,%zu\n", row.budget,
                     row.pipeline.c_str(), row.solvedWith.c_str(), row.elements, m.solveSeconds, m.totalSeconds, m.spp,
                     m.meanRatio[0], m.meanRatio[1], m.meanRatio[2], m.rmse, rp, ratio, int(row.overBudget),
                     row.nonFinitePixels);
    }
    if (csv) std::fclose(csv);
    std::printf(
        "\n* over budget by more than 10%%: the solve or the single sample per pixel the driver always takes "
        "did not fit\n");
    std::printf(
        "RenderPark (rpkCpp at 37e5ff4e, hierarchical Galerkin, one thread): its best RMSE within the budget; "
        "its mean ratios at 0.58 s were %.3f, %.3f, %.3f\n",
        kRenderParkMeanRatios[0], kRenderParkMeanRatios[1], kRenderParkMeanRatios[2]);

    // Per pipeline, at its largest budget: where the light is missing or extra.
    const double largest = *std::max_element(budgets.begin(), budgets.end());
    for (const Pipeline &pipeline : pipelines)
      for (const Row &row : rows) {
        if (row.pipeline != pipeline.name || row.budget != largest) continue;
        std::printf("\n%s at %g s, per object (Σ test / Σ reference over its pixels and the three channels):\n\n",
                    pipeline.name.c_str(), largest);
        std::printf("| object | pixels | ratio |\n|---|---:|---:|\n");
        for (size_t o = 0; o < mask.names.size(); ++o)
          std::printf("| %s | %zu | %.4f |\n", mask.names[o].c_str(), row.median.objectPixels[o],
                      row.median.objectRatio[o]);
        break;
      }
    std::printf("\nload average (1 min) %.2f before, %.2f after\n", loadBefore, bench::loadAverage());
  } catch (const std::exception &error) {
    std::fprintf(stderr, "radiosity_accuracy: %s\n", error.what());
    return 1;
  }
  return 0;
}
