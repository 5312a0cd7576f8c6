// multipass_bias — is multipass's image, on average, the path tracer's? Region by region (issue 17).
//
// An RMSE hides a small image-wide bias under the noise; a region's mean
// does not. For the budget --budget (default 60 s) this renders `multipass`
// and `path` --repeats times each (seeds 1…N, 256×256, --threads, default 2;
// multipass's solve, preview and pass 2 count against its budget, as in
// two_pass_equal_time) and compares the mean of every region, per band,
// with a reference image:
//
//   regions  the pixels whose centre ray first hits each object of the scene
//            (its JSON "name": floor, ceiling, back-wall, left-wall,
//            right-wall, light, mirror-sphere, glass-sphere on the specular
//            box), the caustic under the glass sphere (floor within 110 mm
//            of the point below its centre; only on that scene) and the
//            whole image;
//   ratio    a method's region mean over the reference's, averaged over the
//            repeats, with its standard error from their spread (and the
//            reference's own, from its variance image, added in quadrature);
//   error    the mean over the repeats of |ratio − 1|, averaged over the
//            bands: the error of one image's region mean at that budget, the
//            "mean error" the issue compares at equal time.
//
// The reference is a `path` image with its variance beside it (NAME.var.exr,
// as two_pass_equal_time writes), rendered when missing with --reference-spp
// samples (default 4096, seed 1000003). A region mean converges far faster
// than a pixel: the table prints each region's reference standard error.
//
// Usage: multipass_bias [scene.json] [--budget 60] [--repeats 4] [--threads 2] [--solver auto]
//          [--methods multipass,path] [--reference FILE.exr] [--reference-spp 4096] [--images DIR]
// --images DIR also writes each run's image there as METHOD-REPEAT.exr.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "bench_common.h"
#include "io/image.h"
#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"
#include "render/driver.h"
#include "render/film_image.h"
#include "render/multipass.h"
#include "render/registry.h"
#include "scene/camera.h"
#include "scene/load_scene.h"
#include "util/error.h"

using namespace radiant;
using radiant::bench::secondsSince;
using radiant::bench::variancePathFor;

namespace {

constexpr int kSize = 256;
constexpr uint64_t kReferenceSeed = 1000003;
constexpr int kBands = 3;

struct Region {
  std::string name;
  std::vector<size_t> pixels;
};

/// The regions of the table: one per object the camera sees, the caustic, the image.
std::vector<Region> regionsOf(const Scene &scene, const RayTracer &tracer, const PinholeCamera &camera) {
  std::map<uint32_t, Region> byObject;
  Region caustic{"caustic (floor under glass)", {}}, image{"whole image", {}};
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const size_t p = size_t(y) * kSize + x;
      image.pixels.push_back(p);
      Hit hit;
      if (!tracer.intersect(camera.generateRay(x + 0.5, y + 0.5), hit)) continue;
      const uint32_t object = scene.faces[hit.face].object;
      Region &region = byObject[object];
      region.name = scene.objects[object].name;
      region.pixels.push_back(p);
      // The glass sphere's caustic on the specular box (centre (170, 0, 175) mm below the sphere, as the tests'
      // region).
      if (region.name == "floor") {
        const double dx = hit.position.x - 0.170, dz = hit.position.z - 0.175;
        if (std::hypot(dx, dz) < 0.110) caustic.pixels.push_back(p);
      }
    }
  std::vector<Region> regions;
  for (auto &[object, region] : byObject) regions.push_back(region);
  if (!caustic.pixels.empty()) regions.push_back(caustic);
  regions.push_back(image);
  return regions;
}

/// Per band, the mean of an image over a region.
std::vector<double> regionMeans(const Image &image, const Region &region) {
  std::vector<double> mean(kBands, 0.0);
  for (size_t p : region.pixels)
    for (int b = 0; b < kBands; ++b) mean[b] += image.rgb[3 * p + b];
  for (double &m : mean) m /= double(region.pixels.size());
  return mean;
}

}  // namespace

int main(int argc, char **argv) {
  std::string scenePath = "scenes/cornell-specular/scene.json",
              referencePath = "build/cornell-specular-reference-256.exr", solverName = "auto",
              methodList = "multipass,path", imageFolder;
  int referenceSpp = 4096, threads = 2, repeats = 4;
  double budget = 60;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    bool hasValue = i + 1 < argc;
    if (arg == "--reference" && hasValue)
      referencePath = argv[++i];
    else if (arg == "--reference-spp" && hasValue)
      referenceSpp = std::atoi(argv[++i]);
    else if (arg == "--budget" && hasValue)
      budget = std::atof(argv[++i]);
    else if (arg == "--solver" && hasValue)
      solverName = argv[++i];
    else if (arg == "--methods" && hasValue)
      methodList = argv[++i];
    else if (arg == "--threads" && hasValue)
      threads = std::atoi(argv[++i]);
    else if (arg == "--repeats" && hasValue)
      repeats = std::atoi(argv[++i]);
    else if (arg == "--images" && hasValue)
      imageFolder = argv[++i];
    else if (arg.rfind("--", 0) != 0)
      scenePath = arg;
    else {
      std::fprintf(stderr,
                   "usage: %s [scene.json] [--budget 60] [--repeats 4] [--threads 2] [--solver auto] "
                   "[--methods multipass,path] [--reference FILE.exr] [--reference-spp 4096] [--images DIR]\n",
                   argv[0]);
      return 2;
    }
  }
  std::vector<std::string> methods;
  std::istringstream methodStream(methodList);
  for (std::string item; std::getline(methodStream, item, ',');) methods.push_back(item);
  if (!(budget > 0) || repeats < 2 || referenceSpp < 1) {
    std::fprintf(stderr, "multipass_bias: the budget must be positive, repeats at least 2, reference spp at least 1\n");
    return 2;
  }

  try {
    const double loadBefore = bench::loadAverage();
    Scene scene = loadScene(scenePath);
    RayTracer tracer(scene);
    PinholeCamera camera(scene.camera, kSize, kSize);
    const std::vector<Region> regions = regionsOf(scene, tracer, camera);

    Image reference, referenceVariance;
    const std::string variancePath = variancePathFor(referencePath);
    if (std::filesystem::exists(referencePath) && std::filesystem::exists(variancePath)) {
      reference = readImage(referencePath);
      referenceVariance = readImage(variancePath);
    } else {
      std::fprintf(stderr, "reference: rendering %d spp of path at %dx%d on %d threads\n", referenceSpp, kSize, kSize,
                   threads);
      DriverOptions driver;
      driver.samplesPerPixel = referenceSpp;
      driver.seed = kReferenceSeed;
      driver.threads = threads;
      Film film(kSize, kSize);
      const RenderStats stats = renderImage(camera, *createRenderer("path", tracer, RenderContext{}), driver, film,
                                            makeConsoleProgress("reference"));
      reference = meanImage(film);
      referenceVariance = varianceImage(film);
      if (std::filesystem::path(referencePath).has_parent_path())
        std::filesystem::create_directories(std::filesystem::path(referencePath).parent_path());
      writeImage(reference, referencePath);
      writeImage(referenceVariance, variancePath);
      std::printf("reference rendered: %d spp of path in %.1f s on %d threads\n", stats.samplesPerPixel, stats.seconds,
                  threads);
    }
    if (reference.width != kSize || reference.height != kSize || referenceVariance.width != kSize)
      throw InputError(InputLocation{referencePath}, "the reference and its variance must be 256x256");

    // ratios[method][region][repeat][band]
    std::map<std::string, std::vector<std::vector<std::vector<double>>>> ratios;
    std::vector<std::vector<double>> referenceMeans, referenceErrors;  // [region][band]
    for (const Region &region : regions) {
      referenceMeans.push_back(regionMeans(reference, region));
      std::vector<double> error(kBands, 0.0);
      for (size_t p : region.pixels)
        for (int b = 0; b < kBands; ++b) error[b] += referenceVariance.rgb[3 * p + b];
      for (double &e : error) e = std::sqrt(e) / double(region.pixels.size());
      referenceErrors.push_back(error);
    }
    for (const std::string &method : methods) {
      auto &byRegion = ratios[method];
      byRegion.assign(regions.size(), {});
      for (int repeat = 1; repeat <= repeats; ++repeat) {
        const auto start = std::chrono::steady_clock::now();
        Image image;
        std::string detail;
        if (method == "multipass") {
          MultipassOptions options;
          options.timeBudgetSeconds = budget;
          options.samplesPerPixel = kMaxSamplesPerPixel;
          options.seed = uint64_t(repeat);
          options.threads = threads;
          auto solve = [&](int maxShots) {
            SolverOptions solverOptions;
            solverOptions.solver = maxShots > 0 ? "progressive" : multipassSolverName(solverName, budget);
            solverOptions.seed = uint64_t(repeat);
            solverOptions.threads = threads;
            if (maxShots > 0) solverOptions.maxIterations = maxShots;
            return meshAndSolve(scene, tracer, MeshOptions{}, solverOptions);
          };
          renderMultipass(tracer, camera, kSize, kSize, options, solve,
                          [&](const MultipassPass &pass, const Image &mean, const Image &) {
                            image = mean;
                            detail = describePass(pass);
                          });
        } else {
          Solution solution;
          RenderContext context;
          if (findRenderer(method).needsSolution) {
            SolverOptions solverOptions;
            solverOptions.solver = solverName;
            solverOptions.seed = uint64_t(repeat);
            solverOptions.threads = threads;
            solution = meshAndSolve(scene, tracer, MeshOptions{}, solverOptions);
            context.solution = &solution;
          }
          auto renderer = createRenderer(method, tracer, context);
          DriverOptions driver;
          driver.samplesPerPixel = kMaxSamplesPerPixel;
          driver.seed = uint64_t(repeat);
          driver.threads = threads;
          driver.timeBudgetSeconds = std::max(1e-3, budget - secondsSince(start));
          Film film(kSize, kSize);
          const RenderStats stats = renderImage(camera, *renderer, driver, film);
          image = meanImage(film);
          detail = std::to_string(stats.samplesPerPixel) + " spp";
        }
        std::fprintf(stderr, "%s %d/%d: %.1f s; %s\n", method.c_str(), repeat, repeats, secondsSince(start),
                     detail.c_str());
        if (!imageFolder.empty())  // for `radiant compare --without-emitters` against the reference
          writeImage(image,
                     (std::filesystem::path(imageFolder) / (method + "-" + std::to_string(repeat) + ".exr")).string());
        for (size_t r = 0; r < regions.size(); ++r) {
          std::vector<double> ratio = regionMeans(image, regions[r]);
          for (int b = 0; b < kBands; ++b) ratio[b] /= referenceMeans[r][b];
          byRegion[r].push_back(ratio);
        }
      }
    }

    std::printf("\nmultipass_bias: %s at %dx%d, %d threads, budget %g s, %d repeats, solver '%s'\n", scenePath.c_str(),
                kSize, kSize, threads, budget, repeats, solverName.c_str());
    std::printf(
        "reference: %s. Ratio: mean over the repeats of the region mean over the reference's, ± its standard "
        "error (repeats' spread and the reference's noise); z: (ratio − 1)/SE; error: mean |ratio − 1| of "
        "one image, %% (bands averaged)\n\n",
        referencePath.c_str());
    std::printf("| region | pixels | reference SE %% |");
    for (const std::string &method : methods)
      std::printf(" %s R, G, B ratio (± SE %%) | %s max |z| | %s error %% |", method.c_str(), method.c_str(),
                  method.c_str());
    std::printf("\n|---|---:|---:|");
    for (size_t m = 0; m < methods.size(); ++m) std::printf("---|---:|---:|");
    std::printf("\n");
    for (size_t r = 0; r < regions.size(); ++r) {
      double referenceSe = 0;
      for (int b = 0; b < kBands; ++b) referenceSe += 100 * referenceErrors[r][b] / referenceMeans[r][b] / kBands;
      std::printf("| %s | %zu | %.2f |", regions[r].name.c_str(), regions[r].pixels.size(), referenceSe);
      for (const std::string &method : methods) {
        const auto &runs = ratios[method][r];
        std::string cells;
        double maxZ = 0, error = 0;
        for (int b = 0; b < kBands; ++b) {
          double sum = 0, sumSquares = 0;
          for (const auto &run : runs) sum += run[b], sumSquares += run[b] * run[b], error += std::abs(run[b] - 1);
          const double n = double(runs.size()), mean = sum / n;
          const double spread = std::sqrt(std::max(0.0, (sumSquares - n * mean * mean) / (n - 1)));
          const double se = std::hypot(spread / std::sqrt(n), referenceErrors[r][b] / referenceMeans[r][b]);
          maxZ = std::max(maxZ, std::abs(mean - 1) / se);
          char cell[64];
          std::snprintf(cell, sizeof cell, "%s%.4f (%.2f)", b ? ", " : "", mean, 100 * se);
          cells += cell;
        }
        std::printf(" %s | %.1f | %.2f |", cells.c_str(), maxZ, 100 * error / (kBands * runs.size()));
      }
      std::printf("\n");
    }
    std::printf("\nload average (1 min) %.2f before, %.2f after\n", loadBefore, bench::loadAverage());
  } catch (const std::exception &error) {
    std::fprintf(stderr, "multipass_bias: %s\n", error.what());
    return 1;
  }
  return 0;
}
