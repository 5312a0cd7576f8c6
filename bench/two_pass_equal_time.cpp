// two_pass_equal_time — the two-pass methods against the path tracer at equal wall time.
//
// The question: at the same wall time, how close does each rendering method
// get to the converged image of the Cornell box at 256x256? A two-pass method
// pays for its radiosity solution up front, so here the solve counts against
// the budget. For each budget (--budgets, default 1,2,5,10 s) and method
// (path, interpolate, rushmeier, shirley, kok, reichert, multipass), --repeats times
// (default 3, seeds 1..N for both the solve and the render; multipass solves
// and renders within its budget itself, as `radiant render --method multipass --time`):
//
//   1. meshAndSolve() (--solver, default "auto"; --mesh-size in metres,
//      default the `radiant` CLI's: 1/8 of the scene's largest side) and
//      createRenderer(), timed together as "solve s" (path: setup only);
//   2. renderImage() with timeBudgetSeconds = budget − solve s, on --threads
//      (default 2). At least 1 sample per pixel is always taken, so a method
//      whose solve or single sample exceeds the budget overruns it: such rows
//      are marked "*" (reichert, one form factor and shadow ray per element per
//      sample, is the usual one);
//   3. compares the mean image with the reference: RMSE over all pixels and
//      channels (--without-emitters: leaving out the pixels that show a light
//      and their neighbours, as `radiant compare --without-emitters`, so that
//      the figure is the lit surfaces'), with the reference's own noise removed,
//      √max(0, MSE − mean variance of the reference's pixel means), and the
//      bias of the image mean, |mean test / mean reference − 1| averaged over
//      the bands.
//
// The table holds the medians of the repeats, and each method's RMSE over the
// path tracer's at the same budget. The reference is a `path` image of
// --reference-spp (default 4096) samples, seed 1000003 (independent of the
// test seeds), cached in --reference (default build/cornell-reference-256.exr)
// with its variance image beside it (.var.exr); it is rendered only when that
// file is missing. The load average is printed before and after
// (docs/PERFORMANCE.md: the machine is shared).
//
// Usage: two_pass_equal_time [scene.json] [--budgets 1,2,5,10] [--repeats 3] [--threads 2] [--solver auto]
//          [--mesh-size METRES] [--methods a,b,…] [--reference FILE.exr] [--reference-spp 4096]
//          [--without-emitters] [--csv FILE]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "bench_common.h"
#include "display/emitter_mask.h"
#include "io/compare.h"
#include "io/image.h"
#include "mesh/mesh.h"
#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"
#include "render/driver.h"
#include "render/film_image.h"
#include "render/multipass.h"
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
const char *const kAllMethods = "path,flat,interpolate,rushmeier,shirley,kok,reichert,multipass";

struct Measurement {
  double solveSeconds = 0, totalSeconds = 0, spp = 0, rmse = 0, biasPercent = 0;
  size_t nonFinitePixels = 0;
};

struct Row {
  double budget = 0;
  std::string method;
  Measurement median;
  size_t nonFinitePixels = 0;  // over all repeats
  bool overBudget = false;
};

}  // namespace

int main(int argc, char **argv) {
  std::string scenePath = "scenes/cornell-box/scene.json", referencePath = "build/cornell-reference-256.exr";
  std::string solverName = "auto", csvPath, budgetList = "1,2,5,10", methodList = kAllMethods;
  int referenceSpp = 4096, threads = 2, repeats = 3;
  double meshSizeMetres = 0;  // 0: MeshOptions' default, as `radiant` without --mesh-size
  bool withoutEmitters = false;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    bool hasValue = i + 1 < argc;
    if (arg == "--reference" && hasValue)
      referencePath = argv[++i];
    else if (arg == "--reference-spp" && hasValue)
      referenceSpp = std::atoi(argv[++i]);
    else if (arg == "--budgets" && hasValue)
      budgetList = argv[++i];
    else if (arg == "--solver" && hasValue)
      solverName = argv[++i];
    else if (arg == "--methods" && hasValue)
      methodList = argv[++i];
    else if (arg == "--mesh-size" && hasValue)
      meshSizeMetres = std::atof(argv[++i]);
    else if (arg == "--threads" && hasValue)
      threads = std::atoi(argv[++i]);
    else if (arg == "--repeats" && hasValue)
      repeats = std::atoi(argv[++i]);
    else if (arg == "--without-emitters")
      withoutEmitters = true;
    else if (arg == "--csv" && hasValue)
      csvPath = argv[++i];
    else if (arg.rfind("--", 0) != 0)
      scenePath = arg;
    else {
      std::fprintf(stderr,
                   "usage: %s [scene.json] [--budgets 1,2,5,10] [--repeats 3] [--threads 2] [--solver auto] "
                   "[--mesh-size METRES] [--methods path,shirley,...] [--reference FILE.exr] [--reference-spp 4096] "
                   "[--without-emitters] [--csv FILE]\n",
                   argv[0]);
      return 2;
    }
  }
  std::vector<std::string> methods;
  std::istringstream methodStream(methodList);
  for (std::string item; std::getline(methodStream, item, ',');) methods.push_back(item);
  std::vector<double> budgets;
  std::istringstream budgetStream(budgetList);
  for (std::string item; std::getline(budgetStream, item, ',');) budgets.push_back(std::atof(item.c_str()));
  if (budgets.empty() || repeats < 1 || referenceSpp < 1 ||
      std::any_of(budgets.begin(), budgets.end(), [](double b) { return !(b > 0); })) {
    std::fprintf(stderr, "two_pass_equal_time: budgets must be positive, repeats and reference spp at least 1\n");
    return 2;
  }

  try {
    const double loadBefore = bench::loadAverage();
    Scene scene = loadScene(scenePath);
    RayTracer tracer(scene);
    PinholeCamera camera(scene.camera, kSize, kSize);
    MeshOptions meshOptions;
    meshOptions.maxEdgeLength = meshSizeMetres;
    RenderContext baseOptions;

    // The reference: rendered once, then read from its file.
    Image reference, referenceVariance;
    const std::string variancePath = variancePathFor(referencePath);
    if (std::filesystem::exists(referencePath) && std::filesystem::exists(variancePath)) {
      reference = readImage(referencePath);
      referenceVariance = readImage(variancePath);
      std::fprintf(stderr, "reference: read %s and %s\n", referencePath.c_str(), variancePath.c_str());
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
      if (std::filesystem::path(referencePath).has_parent_path())
        std::filesystem::create_directories(std::filesystem::path(referencePath).parent_path());
      writeImage(reference, referencePath);
      writeImage(referenceVariance, variancePath);
      std::fprintf(stderr, "reference: %d spp in %.1f s, wrote %s and %s\n", stats.samplesPerPixel, stats.seconds,
                   referencePath.c_str(), variancePath.c_str());
      std::printf("reference rendered: %d spp of path in %.1f s on %d threads\n", stats.samplesPerPixel, stats.seconds,
                  threads);
    }
    if (reference.width != kSize || reference.height != kSize || referenceVariance.width != kSize ||
        referenceVariance.height != kSize)
      throw InputError(InputLocation{referencePath}, "the reference and its variance must be 256x256");
    std::vector<uint8_t> leaveOut;  // --without-emitters: the pixels that show a light, and their neighbours
    if (withoutEmitters) {
      if (reference.emitterFraction.empty())
        throw InputError(InputLocation{referencePath},
                         "--without-emitters needs the reference's emitter channel (an EXR written by radiant render)");
      leaveOut = emitterPixelMask(reference);
    }
    // The mean variance of the reference's pixel means, over the compared pixels and channels.
    double referenceNoise = 0;
    size_t comparedValues = 0;
    for (size_t i = 0; i < referenceVariance.rgb.size(); ++i)
      if (leaveOut.empty() || !leaveOut[i / 3]) {
        referenceNoise += referenceVariance.rgb[i];
        ++comparedValues;
      }
    referenceNoise /= double(std::max<size_t>(comparedValues, 1));

    std::vector<Row> rows;
    std::string solvedWith;  // what "auto" picked, and the elements it ended with (hierarchical: leaves)
    size_t solvedElements = 0;
    for (double budget : budgets)
      for (const std::string &method : methods) {
        const bool needsSolution = findRenderer(method).needsSolution;
        std::vector<Measurement> runs;
        for (int repeat = 1; repeat <= repeats; ++repeat) {
          Measurement m;
          const auto start = std::chrono::steady_clock::now();
          if (method == "multipass") {  // its own passes within the budget, solving included: the last image counts
            MultipassOptions options;
            options.timeBudgetSeconds = budget;
            options.samplesPerPixel = kMaxSamplesPerPixel;
            options.seed = uint64_t(repeat);
            options.threads = threads;
            options.context = baseOptions;
            auto solve = [&](int maxShots) {  // the preview progressive, then --solver as the others
              SolverOptions solverOptions;
              solverOptions.solver = maxShots > 0 ? "progressive" : multipassSolverName(solverName, budget);
              solverOptions.seed = uint64_t(repeat);
              solverOptions.threads = threads;
              if (maxShots > 0) solverOptions.maxIterations = maxShots;
              return meshAndSolve(scene, tracer, meshOptions, solverOptions);
            };
            Image last;
            int pairs = 0;
            renderMultipass(tracer, camera, kSize, kSize, options, solve,
                            [&](const MultipassPass &pass, const Image &mean, const Image &) {
                              last = mean;
                              m.spp = pass.controlSamples;  // R samples per pixel, the pairs among them
                              pairs = pass.pairedSamples;
                            });
            m.totalSeconds = secondsSince(start);
            ImageComparison c = compareImages(last, reference, "test", "reference", leaveOut);
            m.rmse = std::sqrt(std::max(0.0, c.average.rmse * c.average.rmse - referenceNoise));
            for (const ChannelComparison &channel : c.channels)
              m.biasPercent += 100 * std::abs(channel.meanRatio - 1) / 3;
            m.nonFinitePixels = c.nonFinitePixels;
            std::fprintf(stderr,
                         "[%gs] %-11s %d/%d: %g spp reading the solution, %d of them paired, total %.2f s, RMSE %.4g, "
                         "bias %.2f%%\n",
                         budget, method.c_str(), repeat, repeats, m.spp, pairs, m.totalSeconds, m.rmse, m.biasPercent);
            runs.push_back(m);
            continue;
          }
          Solution solution;
          RenderContext options = baseOptions;
          if (needsSolution) {
            SolverOptions solverOptions;
            solverOptions.solver = solverName;
            solverOptions.seed = uint64_t(repeat);
            solverOptions.threads = threads;
            solution = meshAndSolve(scene, tracer, meshOptions, solverOptions);
            options.solution = &solution;
            solvedWith = solution.stats.solver;
            solvedElements = solution.elementCount();
          }
          auto renderer = createRenderer(method, tracer, options);
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

          ImageComparison c = compareImages(meanImage(film), reference, "test", "reference", leaveOut);
          m.rmse = std::sqrt(std::max(0.0, c.average.rmse * c.average.rmse - referenceNoise));
          for (const ChannelComparison &channel : c.channels)
            m.biasPercent += 100 * std::abs(channel.meanRatio - 1) / 3;
          m.nonFinitePixels = c.nonFinitePixels;
          std::fprintf(stderr, "[%gs] %-11s %d/%d: solve %.3f s, %d spp, total %.2f s, RMSE %.4g, bias %.3f%%%s\n",
                       budget, method.c_str(), repeat, repeats, m.solveSeconds, stats.samplesPerPixel, m.totalSeconds,
                       m.rmse, m.biasPercent, c.nonFinitePixels ? " (NON-FINITE PIXELS)" : "");
          runs.push_back(m);
        }
        Row row{budget, method};
        auto medianOf = [&](double Measurement::*field) {
          std::vector<double> values;
          for (const Measurement &m : runs) values.push_back(m.*field);
          return median(values);
        };
        row.median.solveSeconds = medianOf(&Measurement::solveSeconds);
        row.median.totalSeconds = medianOf(&Measurement::totalSeconds);
        row.median.spp = medianOf(&Measurement::spp);
        row.median.rmse = medianOf(&Measurement::rmse);
        row.median.biasPercent = medianOf(&Measurement::biasPercent);
        for (const Measurement &m : runs) row.nonFinitePixels += m.nonFinitePixels;
        // The driver's last round is sized from the measured speed, so a few % over is normal; more is the 1-spp floor.
        row.overBudget = row.median.totalSeconds > 1.1 * budget;
        rows.push_back(row);
      }

    const std::string meshSize =
        meshSizeMetres > 0 ? std::to_string(meshSizeMetres) + " m" : "default (1/8 of the largest side)";
    std::printf(
        "\ntwo_pass_equal_time: %s at %dx%d, %d threads, solver '%s' (ran %s, %zu elements), mesh size %s, "
        "median of %d repeats\n",
        scenePath.c_str(), kSize, kSize, threads, solverName.c_str(), solvedWith.c_str(), solvedElements,
        meshSize.c_str(), repeats);
    std::printf("reference: %s, noise removed: mean variance of its pixel means %.3g (RMSE floor %.3g)%s\n\n",
                referencePath.c_str(), referenceNoise, std::sqrt(referenceNoise),
                withoutEmitters ? "; pixels showing a light and their neighbours left out" : "");
    std::printf("| budget s | method | solve s | total s | spp | RMSE | RMSE / path | mean bias %% |\n");
    std::printf("|---:|---|---:|---:|---:|---:|---:|---:|\n");
    FILE *csv = csvPath.empty() ? nullptr : std::fopen(csvPath.c_str(), "w");
    if (!csvPath.empty() && !csv) throw InputError(InputLocation{csvPath}, "cannot open for writing");
    if (csv)
      std::fprintf(csv, "budget_s,method,solve_s,total_s,spp,rmse,rmse_over_path,mean_bias_percent,over_budget\n");
    for (const Row &row : rows) {
      double pathRmse = 0;
      for (const Row &other : rows)
        if (other.budget == row.budget && other.method == "path") pathRmse = other.median.rmse;
      const Measurement &m = row.median;
      double ratio = pathRmse > 0 ? m.rmse / pathRmse : NAN;
      std::printf("| %g | %s%s | %.3f | %.2f | %g | %.4g | %.2f | %.2f |%s\n", row.budget, row.method.c_str(),
                  row.overBudget ? " *" : "", m.solveSeconds, m.totalSeconds, m.spp, m.rmse, ratio, m.biasPercent,
                  row.nonFinitePixels ? "  NON-FINITE PIXELS" : "");
      if (csv)
        std::fprintf(csv, "%g,%s,%.4f,%.4f,%g,%.6g,%.4f,%.4f,%d\n", row.budget, row.method.c_str(), m.solveSeconds,
                     m.totalSeconds, m.spp, m.rmse, ratio, m.biasPercent, int(row.overBudget));
    }
    if (csv) std::fclose(csv);
    std::printf(
        "\n* over budget by more than 10%%: the solve or the single sample per pixel the driver always takes "
        "did not fit\n");
    std::printf("load average (1 min) %.2f before, %.2f after\n", loadBefore, bench::loadAverage());
  } catch (const std::exception &error) {
    std::fprintf(stderr, "two_pass_equal_time: %s\n", error.what());
    return 1;
  }
  return 0;
}
