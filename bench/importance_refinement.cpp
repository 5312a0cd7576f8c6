// importance_refinement — does --importance put the hierarchical solver's
// elements where the view needs them?
//
// The question: at the same number of elements (leaves), how close do
// `interpolate` and `shirley` get to a converged path-traced image when the
// hierarchical solve is view-independent (plain BF refinement) and when it is
// importance-driven for the camera that renders (Smits, Arvo & Salesin 1992,
// radiosity/importance.h)? Two views of the Cornell box: its standard camera,
// which sees nearly every surface, and a corner camera (eye (450, 150, 100) mm,
// target (556, 0, 559.2) mm, the scene's field of view) that sees only the
// far bottom-left corner: the red wall, the floor and the back wall there,
// and the tall block's side.
//
//   1. The plain solve: --mesh-size (default 0.0125 m, the finest leaves) and
//      each of --thresholds (--link-threshold, default 1e-3 and 1e-4); its leaf
//      count N is the budget (it does not depend on the camera).
//   2. Per camera and seed, the importance-driven solve's --link-threshold is
//      tuned until its leaves are within 2 % of N: from the previous seed's
//      (the plain threshold for the first), doubled or halved until N is
//      crossed, then bisected on its logarithm. The seed matters: it moves
//      which links read as partly occluded, and so the leaves, by up to 10 %.
//      A leaf budget in the solver would be the alternative, but the solver's
//      `maxElements` stops wherever the refinement happens to be when it runs
//      out (patch pairs in order), not at the least important links, so the
//      equal count comes from tuning the threshold instead.
//   3. Per camera and solve, --repeats times (seeds 1…N for the solve's shadow
//      rays and the renders): solve (tuned, with importance), render
//      interpolate (--interpolate-spp, default 16) and shirley (--shirley-spp,
//      default 64) at --size² pixels (default 128), and measure the RMSE
//      against the reference with both
//      images' noise removed: √max(0, MSE − mean variance of the reference's
//      pixel means − that of the test's). Pixels that see the light, or touch
//      its edge, are left out: the light's radiance is exact in every method,
//      and the antialiasing noise of the 0-to-18 W·sr⁻¹·m⁻² step along its
//      edge dwarfs every solution error (with them, the noise estimates
//      cancelled the whole MSE). The table holds the medians.
//
// The references are `path` images of --reference-spp (default 2048) samples,
// seed 1000003, cached as importance-reference-{standard,corner}-SIZE.exr
// (with .var.exr beside them) in --reference-dir (default build-importance);
// they are rendered only when missing. The load average is printed before and
// after (docs/PERFORMANCE.md: the machine is shared).
//
// Usage: importance_refinement [scene.json] [--mesh-size 0.0125] [--thresholds 1e-3,1e-4] [--size 128] [--repeats 3]
//          [--threads 2] [--interpolate-spp 16] [--shirley-spp 64] [--reference-spp 2048]
//          [--reference-dir build-importance]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
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

namespace {

constexpr uint64_t kReferenceSeed = 1000003;

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

struct Reference {
  Image mean, variance;
  std::vector<uint8_t> measured;  ///< per pixel: 1 unless it sees the light or touches its edge
};

struct Setup {
  const Scene &scene;
  const RayTracer &tracer;
  int size, threads;
  double meshSize;
};

Solution solve(const Setup &setup, const CameraSettings &camera, bool importance, double threshold, uint64_t seed) {
  MeshOptions meshOptions;
  meshOptions.maxEdgeLength = setup.meshSize;
  SolverOptions options;
  options.solver = "hierarchical";
  options.linkThreshold = threshold;
  options.seed = seed;
  options.threads = setup.threads;
  options.importance = importance;
  options.importanceView.camera = camera;
  options.importanceView.aspect = 1;  // the images here are square
  return meshAndSolve(setup.scene, setup.tracer, meshOptions, options);
}

/// The importance-driven solve whose leaves are within 2 % of `budget` (or the
/// closest found): from `guess`, doubling or halving the threshold until the
/// count is bracketed, then bisecting its logarithm. `threshold` gets the one used.
Solution tunedSolve(const Setup &setup, const CameraSettings &camera, size_t budget, uint64_t seed, double guess,
                    double &threshold) {
  Solution best;
  double bestMiss = INFINITY;
  auto attempt = [&](double t) {  // returns leaves − budget, keeping the closest solve
    Solution s = solve(setup, camera, true, t, seed);
    const double miss = double(s.elementCount()) - double(budget);
    std::fprintf(stderr, "  threshold %.4g: %zu leaves (budget %zu)\n", t, s.elementCount(), budget);
    if (std::abs(miss) < bestMiss) bestMiss = std::abs(miss), best = std::move(s), threshold = t;
    return miss;
  };
  auto closeEnough = [&](double miss) { return std::abs(miss) <= 0.02 * double(budget); };
  double t = guess;
  const double first = attempt(t);
  if (closeEnough(first)) return best;
  // Fewer leaves as the threshold grows: step by 2× until the budget is crossed…
  const double factor = first > 0 ? 2.0 : 0.5;
  double previous = t, miss = first;
  for (int step = 0; step < 30 && (miss > 0) == (first > 0); ++step) {
    previous = t;
    t *= factor;
    miss = attempt(t);
    if (closeEnough(miss)) return best;
  }
  // … then bisect between too many (low) and too few (high).
  double low = std::min(previous, t), high = std::max(previous, t);
  for (int step = 0; step < 20; ++step) {
    const double middle = std::sqrt(low * high);
    miss = attempt(middle);
    if (closeEnough(miss)) break;
    (miss > 0 ? low : high) = middle;
  }
  return best;
}

/// Renders `method` (with `solution` when it reads one) and returns the mean and variance images.
std::pair<Image, Image> render(const Setup &setup, const CameraSettings &cameraSettings, const std::string &method,
                               const Solution *solution, int spp, uint64_t seed) {
  RenderContext options;
  options.solution = solution;
  options.pixelSpreadAngle = 2 * std::tan(0.5 * cameraSettings.verticalFovDegrees * kPi / 180) / setup.size;
  auto renderer = createRenderer(method, setup.tracer, options);
  PinholeCamera camera(cameraSettings, setup.size, setup.size);
  DriverOptions driver;
  driver.samplesPerPixel = spp;
  driver.seed = seed;
  driver.threads = setup.threads;
  Film film(setup.size, setup.size);
  renderImage(camera, *renderer, driver, film);
  return {meanImage(film), varianceImage(film)};
}

/// RMSE over the measured pixels with the noise of both images removed (their mean variances of the pixel means).
double denoisedRmse(const std::pair<Image, Image> &test, const Reference &reference) {
  double squared = 0, noise = 0;
  size_t count = 0;
  for (size_t pixel = 0; pixel < reference.measured.size(); ++pixel) {
    if (!reference.measured[pixel]) continue;
    for (size_t c = pixel * 3; c < pixel * 3 + 3; ++c) {
      const double difference = double(test.first.rgb[c]) - double(reference.mean.rgb[c]);
      squared += difference * difference;
      noise += double(reference.variance.rgb[c]) + double(test.second.rgb[c]);
      ++count;
    }
  }
  return std::sqrt(std::max(0.0, (squared - noise) / double(std::max<size_t>(1, count))));
}

/// 0 for the pixels whose centre or a corner sees an emitter.
std::vector<uint8_t> measuredPixels(const Setup &setup, const CameraSettings &cameraSettings) {
  PinholeCamera camera(cameraSettings, setup.size, setup.size);
  std::vector<uint8_t> measured(size_t(setup.size) * setup.size, 1);
  auto seesLight = [&](double x, double y) {
    Hit hit;
    return setup.tracer.intersect(camera.generateRay(x, y), hit) &&
           setup.scene.materials[hit.material].emission.max() > 0;
  };
  for (int y = 0; y < setup.size; ++y)
    for (int x = 0; x < setup.size; ++x)
      if (seesLight(x + 0.5, y + 0.5) || seesLight(x, y) || seesLight(x + 1, y) || seesLight(x, y + 1) ||
          seesLight(x + 1, y + 1))
        measured[size_t(y) * setup.size + x] = 0;
  return measured;
}

Reference loadOrRenderReference(const Setup &setup, const CameraSettings &camera, const std::string &path, int spp) {
  const std::string variancePath = path.substr(0, path.size() - 4) + ".var.exr";
  Reference reference;
  Image &variance = reference.variance;
  if (std::filesystem::exists(path) && std::filesystem::exists(variancePath)) {
    reference.mean = readImage(path);
    variance = readImage(variancePath);
    std::fprintf(stderr, "reference: read %s\n", path.c_str());
  } else {
    std::fprintf(stderr, "reference: rendering %d spp of path at %dx%d for %s\n", spp, setup.size, setup.size,
                 path.c_str());
    const auto start = std::chrono::steady_clock::now();
    auto images = render(setup, camera, "path", nullptr, spp, kReferenceSeed);
    reference.mean = images.first;
    variance = images.second;
    if (std::filesystem::path(path).has_parent_path())
      std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    writeImage(reference.mean, path);
    writeImage(variance, variancePath);
    std::printf("reference %s: %d spp of path in %.1f s\n", path.c_str(), spp,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  if (reference.mean.width != setup.size || reference.mean.height != setup.size)
    throw InputError(InputLocation{path}, "the reference has another size; delete it or change --size");
  reference.measured = measuredPixels(setup, camera);
  return reference;
}

struct Row {
  std::string camera, solve;
  size_t budget = 0;
  double threshold = 0, leaves = 0, links = 0, seconds = 0, interpolate = 0, shirley = 0;
};

}  // namespace

int main(int argc, char **argv) {
  std::string scenePath = "scenes/cornell-box/scene.json", referenceDir = "build-importance";
  double meshSize = 0.0125;
  std::string thresholdList = "1e-3,1e-4";
  int size = 128, repeats = 3, threads = 2, interpolateSpp = 16, shirleySpp = 64, referenceSpp = 2048;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    bool hasValue = i + 1 < argc;
    if (arg == "--mesh-size" && hasValue)
      meshSize = std::atof(argv[++i]);
    else if (arg == "--thresholds" && hasValue)
      thresholdList = argv[++i];
    else if (arg == "--size" && hasValue)
      size = std::atoi(argv[++i]);
    else if (arg == "--repeats" && hasValue)
      repeats = std::atoi(argv[++i]);
    else if (arg == "--threads" && hasValue)
      threads = std::atoi(argv[++i]);
    else if (arg == "--interpolate-spp" && hasValue)
      interpolateSpp = std::atoi(argv[++i]);
    else if (arg == "--shirley-spp" && hasValue)
      shirleySpp = std::atoi(argv[++i]);
    else if (arg == "--reference-spp" && hasValue)
      referenceSpp = std::atoi(argv[++i]);
    else if (arg == "--reference-dir" && hasValue)
      referenceDir = argv[++i];
    else if (arg.rfind("--", 0) != 0)
      scenePath = arg;
    else {
      std::fprintf(stderr,
                   "usage: %s [scene.json] [--mesh-size 0.0125] [--thresholds 1e-3,1e-4] [--size 128] [--repeats 3] "
                   "[--threads 2] [--interpolate-spp 16] [--shirley-spp 64] [--reference-spp 2048] "
                   "[--reference-dir build-importance]\n",
                   argv[0]);
      return 2;
    }
  }
  std::vector<double> thresholds;
  std::istringstream thresholdStream(thresholdList);
  for (std::string item; std::getline(thresholdStream, item, ',');) thresholds.push_back(std::atof(item.c_str()));
  if (!(meshSize > 0) || thresholds.empty() ||
      std::any_of(thresholds.begin(), thresholds.end(), [](double t) { return !(t > 0); }) || size < 8 || repeats < 1 ||
      interpolateSpp < 1 || shirleySpp < 1 || referenceSpp < 1) {
    std::fprintf(stderr, "importance_refinement: sizes, counts and the threshold must be positive\n");
    return 2;
  }

  try {
    const double loadBefore = bench::loadAverage();
    const auto start = std::chrono::steady_clock::now();
    Scene scene = loadScene(scenePath);
    RayTracer tracer(scene);
    const Setup setup{scene, tracer, size, threads, meshSize};
    const double mm = 0.001;  // the corner camera is given in the Cornell box's millimetres
    CameraSettings corner = scene.camera;
    corner.eye = Vec3{450 * mm, 150 * mm, 100 * mm};
    corner.target = Vec3{556 * mm, 0, 559.2 * mm};
    const std::vector<std::pair<std::string, CameraSettings>> cameras = {{"standard", scene.camera},
                                                                         {"corner", corner}};

    std::vector<Reference> references;
    for (const auto &[name, camera] : cameras)
      references.push_back(loadOrRenderReference(
          setup, camera, referenceDir + "/importance-reference-" + name + "-" + std::to_string(size) + ".exr",
          referenceSpp));
    std::vector<Row> rows;
    for (double threshold : thresholds)
      for (size_t view = 0; view < cameras.size(); ++view) {
        const auto &[name, camera] = cameras[view];
        const Reference &reference = references[view];
        // The budget: the plain solve's leaves (view-independent, the same for both cameras).
        const size_t budget = solve(setup, scene.camera, false, threshold, 1).elementCount();
        double guess = threshold;  // where the importance-driven threshold search starts
        for (bool importance : {false, true}) {
          Row row;
          row.camera = name;
          row.solve = importance ? "importance" : "plain";
          row.budget = budget;
          std::vector<double> thresholdsUsed, leaves, links, seconds, interpolate, shirley;
          for (int repeat = 1; repeat <= repeats; ++repeat) {
            double used = threshold;
            Solution s = importance ? tunedSolve(setup, camera, budget, uint64_t(repeat), guess, used)
                                    : solve(setup, camera, false, threshold, uint64_t(repeat));
            if (importance) guess = used;
            thresholdsUsed.push_back(used);
            leaves.push_back(double(s.elementCount()));
            links.push_back(double(s.links.size()));
            seconds.push_back(s.stats.seconds);
            interpolate.push_back(
                denoisedRmse(render(setup, camera, "interpolate", &s, interpolateSpp, uint64_t(repeat)), reference));
            shirley.push_back(
                denoisedRmse(render(setup, camera, "shirley", &s, shirleySpp, uint64_t(repeat)), reference));
            std::fprintf(stderr, "%s %s %d/%d: %zu leaves, %.2f s, RMSE interpolate %.4g, shirley %.4g\n", name.c_str(),
                         row.solve.c_str(), repeat, repeats, s.elementCount(), s.stats.seconds, interpolate.back(),
                         shirley.back());
          }
          row.threshold = median(thresholdsUsed);
          row.leaves = median(leaves);
          row.links = median(links);
          row.seconds = median(seconds);
          row.interpolate = median(interpolate);
          row.shirley = median(shirley);
          rows.push_back(row);
        }
      }

    std::printf(
        "\nimportance_refinement: %s at %dx%d, hierarchical, mesh size %g m, plain --link-threshold %s, "
        "%d threads, median of %d repeats\n",
        scenePath.c_str(), size, size, meshSize, thresholdList.c_str(), threads, repeats);
    std::printf(
        "references: path, %d spp; RMSE with both images' noise removed, pixels on the light's edge left "
        "out; interpolate %d spp, shirley %d spp\n\n",
        referenceSpp, interpolateSpp, shirleySpp);
    std::printf(
        "| budget | camera | solve | --link-threshold | leaves | links | solve s | RMSE interpolate | "
        "RMSE shirley |\n");
    std::printf("|---:|---|---|---:|---:|---:|---:|---:|---:|\n");
    for (const Row &r : rows)
      std::printf("| %zu | %s | %s | %.3g | %.0f | %.0f | %.2f | %.4g | %.4g |\n", r.budget, r.camera.c_str(),
                  r.solve.c_str(), r.threshold, r.leaves, r.links, r.seconds, r.interpolate, r.shirley);
    std::printf("\n| budget | camera | RMSE importance / plain: interpolate | shirley |\n|---:|---|---:|---:|\n");
    for (size_t i = 0; i + 1 < rows.size(); i += 2)
      std::printf("| %zu | %s | %.2f | %.2f |\n", rows[i].budget, rows[i].camera.c_str(),
                  rows[i + 1].interpolate / rows[i].interpolate, rows[i + 1].shirley / rows[i].shirley);
    std::printf("\ntotal %.0f s; load average (1 min) %.2f before, %.2f after\n",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), loadBefore,
                bench::loadAverage());
  } catch (const std::exception &error) {
    std::fprintf(stderr, "importance_refinement: %s\n", error.what());
    return 1;
  }
  return 0;
}
