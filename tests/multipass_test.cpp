// The progressive multi-pass method (Chen et al. 1991; render/multipass.h,
// docs/multipass.md): every light path counted once, convergence to the path
// tracer, and the caustic map's brightness.
#include "render/multipass.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>

#include "film_metrics.h"
#include "radiosity/form_factor.h"
#include "radiosity/solver.h"
#include "render/caustic_photons.h"
#include "render/driver.h"
#include "render/registry.h"
#include "render_helpers.h"
#include "sanitizer.h"
#include "scene/load_scene.h"
#include "test_scenes.h"
#include "util/file_extension.h"
#include "util/interrupt.h"
#include "util/random.h"
#include "util/sampling.h"

namespace radiant {
namespace {

const std::string kSpecularBox = std::string(RADIANT_SOURCE_DIR) + "/scenes/cornell-specular/scene.json";

Film renderWith(const RayTracer &tracer, const RenderContext &options, const std::string &method, int size, int spp,
                uint64_t seed = 1) {
  PinholeCamera camera(tracer.scene().camera, size, size);
  Film film(size, size);
  DriverOptions driver;
  driver.samplesPerPixel = spp;
  driver.seed = seed;
  renderImage(camera, *createRenderer(method, tracer, options), driver, film);
  return film;
}

/// Mean green radiance over a set of pixels and its standard error.
struct Mean {
  double value = 0, error = 0;
};
Mean regionMean(const Film &film, const std::vector<size_t> &pixels) {
  Mean m;
  double variance = 0;
  for (size_t p : pixels) m.value += film.mean(p)[1], variance += film.varianceOfMean(p)[1];
  m.value /= pixels.size();
  m.error = std::sqrt(variance) / pixels.size();
  return m;
}

/// The pixels of the glass sphere's caustic on the floor, with a margin wider
/// than the photon radius (so the density estimate's blur keeps its energy inside).
std::vector<size_t> causticRegion(const Scene &scene, int size) {
  // The floor under the glass sphere (centre (170, 0, 175) mm, radius 95): a
  // disc of 110 mm around the point below its centre, as the camera sees it.
  return test::pixelsWhere(scene, size, [](const Hit &hit) {
    const Vec3 d = hit.position - Vec3{0.170, 0, 0.175};
    return hit.position.y < 1e-3 && std::hypot(d.x, d.z) < 0.110;
  });
}

std::vector<size_t> allPixels(int size) {
  std::vector<size_t> pixels(size_t(size) * size);
  for (size_t p = 0; p < pixels.size(); ++p) pixels[p] = p;
  return pixels;
}

/// Multipass's solver on a mesh of `meshSize` metres: progressive
/// refinement for the preview and (to `tolerance`, 0: its default) for the rest.
MultipassSolver progressiveOn(const RayTracer &tracer, double meshSize, double tolerance = 0) {
  return [&tracer, meshSize, tolerance](int maxShots) {
    MeshOptions mesh;
    mesh.maxEdgeLength = meshSize;
    SolverOptions solver;
    solver.solver = "progressive";
    if (tolerance > 0) solver.tolerance = tolerance;
    if (maxShots > 0) solver.maxIterations = maxShots;
    return meshAndSolve(tracer.scene(), tracer, mesh, solver);
  };
}

// Counting once (the issue's first test), for the caustic map (pass 2's): path
// tracing that leaves L S+ D at non-specular vertices to the map agrees
// with the plain path tracer over the whole image and over the caustic under
// the glass sphere, within 4σ of both plus 2 % for the density estimate's blur
// (the region's margin, 15 mm, is wider than the 8 mm radius, so only what the
// blur carries across the disc's rim — a share of the rim's caustic — leaves
// it). With the map's photons left out (exclusion only) the caustic region
// drops far below; with the map added to the plain path tracer (no exclusion)
// it rises far above: a missing or doubled path class fails the test.
TEST(Multipass, EveryLightPathIsCountedOnce) {
  Scene scene = loadScene(kSpecularBox);
  RayTracer tracer(scene);
  const int size = 40;
  const std::vector<size_t> caustic = causticRegion(scene, size), all = allPixels(size);
  ASSERT_GT(caustic.size(), 20u);
  const CausticPhotonMap map(tracer, 400000, 7, 0.008), none(tracer, 0, 7, 0.008);
  ASSERT_GT(map.stored(), 10000u);
  RenderContext plain, withMap, exclusionOnly;
  withMap.caustics = &map;
  exclusionOnly.caustics = &none;
  const Film path = renderWith(tracer, plain, "path", size, 1024);
  const Film multipass = renderWith(tracer, withMap, "path", size, 256, 2);
  const Film missing = renderWith(tracer, exclusionOnly, "path", size, 256, 2);
  for (const auto *region : {&all, &caustic}) {
    const Mean a = regionMean(path, *region), b = regionMean(multipass, *region);
    EXPECT_NEAR(b.value, a.value, 4 * std::hypot(a.error, b.error) + 0.02 * a.value)
        << (region == &all ? "whole image" : "caustic region");
  }
  // The caustic is about 3/4 of the region's light (measured 0.12 of 0.16):
  // a missing class leaves about 1/4, a doubled one about 7/4.
  const Mean a = regionMean(path, caustic), b = regionMean(multipass, caustic), c = regionMean(missing, caustic);
  EXPECT_LT(c.value, 0.5 * a.value) << "without the map the caustic must be missing";
  EXPECT_GT(a.value + (b.value - c.value), 1.5 * a.value) << "the map on top of path must double it";
  std::cout << "caustic region: path " << a.value << " ± " << a.error << ", multipass " << b.value << " ± " << b.error
            << ", without the map " << c.value << "\n";
}

/// Path with a caustic map against plain path over the whole image of a
/// small scene, within 4σ of both + 2 % blur.
void expectMapAgreesWithPath(const std::string &json, const std::string &what) {
  Scene scene = parseSceneJson(json, what + ".json");
  RayTracer tracer(scene);
  const CausticPhotonMap map(tracer, 400000, 11, 0.02);
  RenderContext plain, withMap;
  withMap.caustics = &map;
  const int size = 24;
  const Film path = renderWith(tracer, plain, "path", size, 2048),
             multipass = renderWith(tracer, withMap, "path", size, 512, 5);
  const Mean a = regionMean(path, allPixels(size)), b = regionMean(multipass, allPixels(size));
  EXPECT_NEAR(b.value, a.value, 4 * std::hypot(a.error, b.error) + 0.02 * a.value) << what;
  std::cout << what << ": path " << a.value << " ± " << a.error << ", with the map " << b.value << " ± " << b.error
            << " (" << map.stored() << " photons)\n";
}

// Review cases the Cornell test cannot see. A floor behind a single glass
// pane: photons carry power, which is not scaled by (η_i/η_t)² across the
// interface (scaled, the map would be 1/η² = 0.44 of the truth). A glossy
// floor lit through a mirror: the glossy lobe's caustic is not in the map,
// so the path tracer must keep finding it (dropped, the highlight would vanish).
TEST(Multipass, TheMapAgreesWithPathThroughAPaneAndOnAGlossyFloor) {
  const std::string room = R"({"camera": {"eye": [0, 1.6, 0.01], "target": [0, 0, 0], "up": [0, 0, 1], "fov": 60},
    "materials": {"floor": MATERIAL, "glass": {"type": "dielectric", "ior": 1.5},
                  "mirror": {"type": "mirror", "reflectance": 0.9},
                  "light": {"reflectance": 0, "emission": 20}},
    "objects": [
      {"type": "quad", "material": "floor", "vertices": [[-2, 0, -2], [-2, 0, 2], [2, 0, 2], [2, 0, -2]]},
      OBJECTS,
      {"type": "quad", "material": "light", "vertices": [[-0.2, 2, -0.2], [0.2, 2, -0.2], [0.2, 2, 0.2], [-0.2, 2, 0.2]]}]})";
  auto scene = [&](const std::string &material, const std::string &objects) {
    std::string s = room;
    s.replace(s.find("MATERIAL"), 8, material);
    s.replace(s.find("OBJECTS"), 7, objects);
    return s;
  };
  // The pane at 1 m, between the light (2 m) and the floor; the camera at 1.6 m sees the floor through it.
  expectMapAgreesWithPath(
      scene(R"({"reflectance": 0.5})",
            R"({"type": "quad", "material": "glass", "vertices": [[-1, 1, -1], [-1, 1, 1], [1, 1, 1], [1, 1, -1]]})"),
      "floor behind a pane");
  // A mirror wall beside the light throws its image onto a glossy floor.
  expectMapAgreesWithPath(
      scene(
          R"({"type": "glossy", "reflectance": 0.3, "specular": 0.5, "roughness": 0.05})",
          R"({"type": "quad", "material": "mirror", "vertices": [[1, 0, -2], [1, 0, 2], [1, 2.5, 2], [1, 2.5, -2]]})"),
      "glossy floor and a mirror");
}

// The control variate's pairs (render/control_variate.h) are the two
// estimators, from the same random numbers: the control is exactly the
// low-frequency pass's reading of the solution (with the pass's map of light
// after a specular bounce where it has one), and control + difference
// exactly `path`'s sample (no map in P). So E[P] = E[path] by construction.
TEST(Multipass, PairedSamplesAreTheTwoEstimatorsFromTheSameNumbers) {
  Scene scene = loadScene(kSpecularBox);
  RayTracer tracer(scene);
  MeshOptions mesh;
  mesh.maxEdgeLength = 0.25;  // a poor solution: R and P differ a lot
  SolverOptions solver;
  solver.solver = "progressive";
  const Solution coarse = meshAndSolve(scene, tracer, mesh, solver);
  const int size = 24, spp = 8;
  PinholeCamera camera(scene.camera, size, size);
  // Without a map, and with the map of light after a specular bounce that R
  // reads with the solution (passes 3…): P stays `path`'s sample.
  const CausticPhotonMap map(tracer, 100000, 5, 0, true);
  ASSERT_GT(map.stored(), 0u);
  for (const bool withMap : {false, true}) {
    RenderContext reading, plain;
    reading.solution = &coarse, reading.readSolutionDepth = 1;
    if (withMap) reading.specularLastLight = &map;
    const Film controls = renderWith(tracer, reading, "path", size, spp, 3);
    const Film paths = renderWith(tracer, plain, "path", size, spp, 3);
    Film paired(size, size, {"control"});
    DriverOptions driver;
    driver.samplesPerPixel = spp;
    driver.seed = 3;
    renderImage(camera, *createRenderer("path", tracer, reading), driver, paired);
    const PairedFilm pairs(paired, "control");
    double differs = 0;
    for (size_t p = 0; p < pairs.pixelCount(); ++p)
      for (int b = 0; b < kBandCount; ++b) {
        EXPECT_EQ(pairs.sumControl[p][b], controls.sum[p][b]) << "pixel " << p << (withMap ? ", map" : "");
        const double total = pairs.sumControl[p][b] + pairs.sumDifference[p][b];
        EXPECT_NEAR(total, paths.sum[p][b], 1e-9 * std::max(1.0, paths.sum[p][b]))
            << "pixel " << p << (withMap ? ", map" : "");
        differs += std::abs(pairs.sumDifference[p][b]);
      }
    EXPECT_GT(differs, 0.01 * size * size) << "the coarse solution must make R and P differ";
  }
}

// The caustic map's brightness: with photons forced through a mirror, the
// light a mirror throws onto the floor is ρ_mirror × what a light of the same
// shape at the mirrored position would give: here, the map's irradiance under
// a horizontal mirror below a downward light equals the contour formula of the
// light's mirror image (C&W ch. 4), times the mirror's reflectance.
TEST(Multipass, CausticMapIrradianceMatchesTheMirrorImageOfTheLight) {
  Scene scene;
  scene.objects.push_back({"test", "test"});
  // A small light at height 1 facing up, a mirror ceiling at height 2 facing
  // down, a floor at 0 facing up: the floor sees the light only via the mirror
  // (the light's back is dark), as a light at height 3 facing down.
  scene.positions = {{-2, 0, -2},     {-2, 0, 2},     {2, 0, 2},     {2, 0, -2},      // floor
                     {-0.1, 1, -0.1}, {-0.1, 1, 0.1}, {0.1, 1, 0.1}, {0.1, 1, -0.1},  // light, facing +y
                     {-4, 2, -4},     {4, 2, -4},     {4, 2, 4},     {-4, 2, 4}};     // mirror, facing −y
  Material white, light, mirror;
  white.name = "white", white.diffuse = Bands(0.5);
  light.name = "light", light.diffuse = Bands(0.0), light.emission = Bands(10.0);
  mirror.name = "mirror", mirror.kind = MaterialKind::Mirror, mirror.diffuse = Bands(0.0), mirror.specular = Bands(0.8);
  scene.materials = {white, light, mirror};
  test::addQuads(scene, {0, 1, 2});
  RayTracer tracer(scene);
  const CausticPhotonMap map(tracer, 2000000, 3, 0.05);
  const Vec3 image[4] = {{-0.1, 3, -0.1}, {0.1, 3, -0.1}, {0.1, 3, 0.1}, {-0.1, 3, 0.1}};
  // Points outside the light's own shadow (a photon bound for floor point p
  // crosses y = 1 at 2p/3 + x/3, so |p| ≤ 0.1 lies behind the light quad).
  ASSERT_FALSE(map.photons().empty());
  const double photonPower = map.photons()[0].power[1];  // every photon carries Φ/N × 0.8 (the mirror)
  for (double x : {0.3, 0.5, 0.8}) {
    const Vec3 p{x, 0, 0};
    const double exact = 0.8 * kPi * 10 * formFactorPointToPolygon(p, {0, 1, 0}, image);
    // The expected photon count in the disc follows from the exact irradiance;
    // its Poisson noise is 1/√N relative, and the disc's blur over a field
    // that varies by < 1 % across 5 cm adds < 0.5 %.
    const double photonsInDisc = exact * kPi * 0.05 * 0.05 / photonPower;
    ASSERT_GT(photonsInDisc, 100) << "x " << x;
    EXPECT_NEAR(map.irradiance(p, {0, 1, 0})[1], exact, exact * (4 / std::sqrt(photonsInDisc) + 0.005)) << "x " << x;
  }
}

// The map's grid finds exactly the photons a scan of all of them finds: at
// each photon, at points near the rim of its disc (inside and outside), and
// at points on the cells' boundaries (multiples of 2r), where a photon listed
// in too few cells would be missed.
TEST(Multipass, TheMapGridFindsWhatAScanFinds) {
  Scene scene = loadScene(kSpecularBox);
  RayTracer tracer(scene);
  const double r = 0.02;
  const CausticPhotonMap map(tracer, 100000, 5, r);
  ASSERT_GT(map.stored(), 3000u);
  auto scan = [&](const Vec3 &x, const Vec3 &n) {
    Bands sum(0.0);
    for (const CausticPhoton &photon : map.photons()) {
      const Vec3 d = photon.position - x;
      if (dot(d, d) <= r * r && dot(photon.normal, n) > 0.5 && std::abs(dot(d, n)) < 0.25 * r) sum += photon.power;
    }
    return sum / (kPi * r * r);
  };
  Pcg32 rng(9, 9);
  int checked = 0, nonZero = 0;
  for (size_t i = 0; i < map.photons().size(); i += 37) {
    const CausticPhoton &photon = map.photons()[i];
    const Frame frame = Frame::fromNormal(photon.normal);
    std::vector<Vec3> points = {photon.position};
    for (double rim : {0.999, 1.001}) {
      const double angle = 2 * kPi * rng.next();
      points.push_back(photon.position + frame.toWorld(Vec3{std::cos(angle), std::sin(angle), 0}) * (rim * r));
    }
    Vec3 boundary = photon.position;  // the nearest cell boundary along x, in the photon's plane if it is one
    boundary.x = std::round(boundary.x / (2 * r)) * 2 * r;
    points.push_back(boundary);
    for (const Vec3 &x : points) {
      const Bands grid = map.irradiance(x, photon.normal), all = scan(x, photon.normal);
      for (int b = 0; b < kBandCount; ++b) EXPECT_NEAR(grid[b], all[b], 1e-5 * std::max(1.0, all[b])) << "photon " << i;
      ++checked, nonZero += all[1] > 0;
    }
  }
  EXPECT_GT(nonZero, checked / 2);
}

// The furnace holds for multipass: every pass (preview, high frequency,
// the combined passes 3…) shows radiance 2 (E/(1−ρ)) within its noise and
// the solution's convergence.
TEST(Multipass, TheFurnaceHoldsInEveryPass) {
  Scene scene = test::furnace(1.0, 0.5);
  RayTracer tracer(scene);
  PinholeCamera camera(scene.camera, 16, 16);
  MultipassOptions options;
  options.samplesPerPixel = 32;
  options.photonsPerPass = 1000;
  const MultipassSolver solve = progressiveOn(tracer, 0.25, 1e-6);
  int passes = 0;
  renderMultipass(tracer, camera, 16, 16, options, solve,
                  [&](const MultipassPass &pass, const Image &mean, const Image &variance) {
                    double sum = 0, var = 0;
                    for (size_t i = 1; i < mean.rgb.size(); i += 3) sum += mean.rgb[i], var += variance.rgb[i];
                    const double n = double(mean.rgb.size() / 3);
                    // Later passes read the converged solution (tolerance 1e-6) or nothing: 4σ.
                    // The preview reads a solution stopped after 32 of ~100 shots, whose ambient
                    // term restores the unshot energy on average but not its distribution over
                    // the walls the camera sees: allowed 5 % (measured 1.8 %).
                    EXPECT_NEAR(sum / n, 2.0, pass.index == 1 ? 0.1 : 4 * std::sqrt(var) / n + 1e-3) << pass.name;
                    ++passes;
                  });
  EXPECT_GE(passes, 5);
}

// The schedule of passes 3… ends, and without a time budget depends only
// on the seed and --spp: the same image on 1 and on 2 threads, bit for bit.
// Also at --spp 1 and 2, on a 1 × 1 image, and in a scene without light
// (D ≡ 0, so every pass is a pair: the loop must still end).
TEST(Multipass, TheScheduleEndsAndIsDeterministic) {
  Scene scene = loadScene(kSpecularBox);
  RayTracer tracer(scene);
  auto run = [&](const RayTracer &t, int size, int spp, int threads, int *passes = nullptr) {
    PinholeCamera camera(t.scene().camera, size, size);
    MultipassOptions options;
    options.samplesPerPixel = spp;
    options.threads = threads;
    options.photonsPerPass = 5000;
    const MultipassSolver solve = progressiveOn(t, 0.25);
    Image last;
    int count = 0, units2 = 0;  // work of passes 3… in half units
    renderMultipass(t, camera, size, size, options, solve,
                    [&](const MultipassPass &pass, const Image &mean, const Image &) {
                      last = mean, ++count;
                      if (pass.index >= 3) units2 += pass.samplesPerPixel * (pass.unbiased ? 2 : 1);
                    });
    EXPECT_LE(units2, 2 * spp) << "--spp caps the work";
    EXPECT_GE(units2, 2 * spp - 1) << "--spp is used";
    if (passes) *passes = count;
    return last;
  };
  const Image one = run(tracer, 12, 24, 1), two = run(tracer, 12, 24, 2);
  ASSERT_EQ(one.rgb.size(), two.rgb.size());
  for (size_t i = 0; i < one.rgb.size(); ++i) ASSERT_EQ(one.rgb[i], two.rgb[i]) << "value " << i;
  int passes = 0;
  run(tracer, 8, 1, 2, &passes);
  EXPECT_EQ(passes, 3);  // the preview, pass 2 and one pair
  run(tracer, 8, 2, 2, &passes);
  EXPECT_EQ(passes, 3);
  run(tracer, 1, 8, 2, &passes);
  EXPECT_GE(passes, 4);
  Scene dark = test::furnace(0.0, 0.5);
  RayTracer darkTracer(dark);
  const Image black = run(darkTracer, 8, 16, 2, &passes);
  for (float v : black.rgb) EXPECT_EQ(v, 0.0f);
}

// A time budget, at the two ends where the outcome does not depend on the
// machine's speed (how much of a budget a render uses in between is measured
// by bench/multipass_budget, docs/PERFORMANCE.md). A budget of 1 ns is spent
// by the time the preview is shown, so the preview is the only pass.
// --checkpoint (render/multipass_checkpoint.h): a render stopped in pass 3
// (before its first save), halfway through pass 5 (its film in its own file)
// or as pass 6 ends, then resumed, ends with the uninterrupted run's image,
// bit for bit, and leaves no checkpoint behind.
TEST(Multipass, AResumedRenderEndsWithTheUninterruptedImage) {
  Scene scene = loadScene(kSpecularBox);
  RayTracer tracer(scene);
  constexpr int kSize = 16;
  PinholeCamera camera(scene.camera, kSize, kSize);
  const std::string path =
      (std::filesystem::temp_directory_path() / ("radiant-multipass-" + std::to_string(::getpid()) + ".bin")).string();
  MultipassOptions options;
  options.samplesPerPixel = 96;
  options.photonsPerPass = 5000;
  options.checkpointJob = "test job\n";
  options.checkpointIntervalSeconds = 0;  // the pass in progress saves after every wave
  const MultipassSolver solve = progressiveOn(tracer, 0.25);
  // Runs to the end or to the stop; the last image written, and the passes rendered.
  auto run = [&](const std::string &stopIn, double stopAt, bool resume, int *firstPass = nullptr) {
    MultipassOptions o = options;
    o.checkpointPath = stopIn == "none" && !resume ? "" : path;
    o.resume = resume;
    Image last;
    int first = 0;
    renderMultipass(
        tracer, camera, kSize, kSize, o, solve,
        [&](const MultipassPass &pass, const Image &mean, const Image &) {
          if (interruptRequested()) return;
          last = mean;
          if (!first) first = pass.index;
        },
        [&](const std::string &label) -> ProgressCallback {
          if (label.rfind(stopIn + " ", 0) != 0) return {};
          return [stopAt](const Progress &p) {
            if (p.fraction >= stopAt) requestInterrupt();
          };
        });
    if (firstPass) *firstPass = first;
    return last;
  };
  const Image whole = run("none", 0, false);
  for (const auto &[pass, fraction] :
       std::vector<std::pair<std::string, double>>{{"multipass 3", 0.0}, {"multipass 5", 0.5}, {"multipass 6", 1.0}}) {
    std::filesystem::remove(path);
    run(pass, fraction, false);
    ASSERT_TRUE(interruptRequested());
    clearInterrupt();
    EXPECT_TRUE(std::filesystem::exists(path)) << "stopped in " << pass;
    int firstPass = 0;
    const Image resumed = run("none", 0, true, &firstPass);
    EXPECT_GE(firstPass, 3) << "passes 1 and 2 are not redone";
    ASSERT_EQ(resumed.rgb.size(), whole.rgb.size());
    size_t differing = 0;
    for (size_t i = 0; i < whole.rgb.size(); ++i) differing += resumed.rgb[i] != whole.rgb[i];
    EXPECT_EQ(differing, 0u) << "stopped in " << pass;
    EXPECT_FALSE(std::filesystem::exists(path));
    for (int k = 3; k < 20; ++k) EXPECT_FALSE(std::filesystem::exists(passFilePath(path, k))) << k;
  }
}

TEST(Multipass, ASpentBudgetEndsTheRenderAfterThePreview) {
  Scene scene = loadScene(kSpecularBox);
  RayTracer tracer(scene);
  const int size = 8;
  PinholeCamera camera(scene.camera, size, size);
  MultipassOptions options;
  options.timeBudgetSeconds = 1e-9;
  options.photonsPerPass = 5000;
  std::vector<int> passes;
  renderMultipass(tracer, camera, size, size, options, progressiveOn(tracer, 0.25),
                  [&](const MultipassPass &pass, const Image &, const Image &) { passes.push_back(pass.index); });
  EXPECT_EQ(passes, std::vector<int>{1});
}

// A budget of 10⁶ s (11 days) is never spent here, so the schedule planned
// from measured times (not the cost units of a render without a budget) must
// go on until --spp is used, however fast or slow the passes are: nothing but
// the budget or the cap may end it. (The review's case, a pass too short for
// one sample ending the render early, happens only as a budget runs out,
// where the bench measures it.)
TEST(Multipass, ABudgetNotSpentRunsToTheSampleCap) {
  Scene scene = loadScene(kSpecularBox);
  RayTracer tracer(scene);
  const int size = 8, spp = 24;
  PinholeCamera camera(scene.camera, size, size);
  MultipassOptions options;
  options.timeBudgetSeconds = 1e6;
  options.samplesPerPixel = spp;
  options.photonsPerPass = 5000;
  int last = 0, units2 = 0;  // the work of passes 3… in half units, as TheScheduleEndsAndIsDeterministic counts it
  renderMultipass(tracer, camera, size, size, options, progressiveOn(tracer, 0.25),
                  [&](const MultipassPass &pass, const Image &, const Image &) {
                    EXPECT_EQ(pass.index, last + 1) << "passes in order, none left out";
                    last = pass.index;
                    if (pass.index < 3) return;
                    EXPECT_GE(pass.samplesPerPixel, 1) << "pass " << pass.index;
                    units2 += pass.samplesPerPixel * (pass.unbiased ? 2 : 1);
                  });
  EXPECT_GE(last, 4) << "the preview, pass 2, the first pairs and at least one planned pass";
  EXPECT_LE(units2, 2 * spp) << "--spp caps the work";
  EXPECT_GE(units2, 2 * spp - 1) << "--spp is used: the budget did not end the render";
}

// Under a short budget the previews must not eat it (multipass.cpp,
// kOwnSolveBudget and kHighFrequencyBudget): measured against the preview's
// time t₁, a budget under 10 t₁ keeps the preview's solution for the
// control variate (no second solve) and skips pass 2; one under 25 × the
// time spent after the solve skips pass 2 only. The preview is made to
// take 0.15 s (a sleep, so that the outcome does not depend on the machine's
// speed: the 8 × 8 image's passes take milliseconds); the assertions hold
// unless pass 1's 8 × 8 render stalls for 0.15 s (3 s would then be under 10 t₁).
TEST(Multipass, AShortBudgetSkipsWhatNoUnbiasedPassUses) {
  Scene scene = loadScene(kSpecularBox);
  RayTracer tracer(scene);
  const int size = 8;
  PinholeCamera camera(scene.camera, size, size);
  const Solution preview = progressiveOn(tracer, 0.25)(32), full = progressiveOn(tracer, 0.25)(0);
  struct Outcome {
    std::vector<int> passes;
    int fullSolves = 0;
  };
  auto run = [&](double budget) {
    Outcome outcome;
    MultipassOptions options;
    options.timeBudgetSeconds = budget;
    options.samplesPerPixel = 1 << 20;
    options.photonsPerPass = 5000;
    const MultipassSolver solve = [&](int maxShots) {
      if (maxShots == 0) return ++outcome.fullSolves, full;
      std::this_thread::sleep_for(std::chrono::milliseconds(150));
      return preview;
    };
    renderMultipass(
        tracer, camera, size, size, options, solve,
        [&](const MultipassPass &pass, const Image &, const Image &) { outcome.passes.push_back(pass.index); });
    return outcome;
  };
  const Outcome veryShort = run(1.0);  // under 7 t₁
  EXPECT_EQ(veryShort.fullSolves, 0) << "the preview's solution serves as the control variate";
  ASSERT_GE(veryShort.passes.size(), 2u);
  EXPECT_EQ(veryShort.passes[0], 1);
  EXPECT_EQ(veryShort.passes[1], 3) << "no pass 2";
  const Outcome shortish = run(3.0);  // 20 t₁: its own solve, still no pass 2 (it would need 25 × 0.15 s)
  EXPECT_EQ(shortish.fullSolves, 1);
  ASSERT_GE(shortish.passes.size(), 2u);
  EXPECT_EQ(shortish.passes[1], 3) << "no pass 2";
}

// Converging (the issue's second test): with a deliberately coarse first-pass
// mesh, shirley's error against a converged path image stays above a floor
// (its interpolated indirect light is the coarse solution's), while the
// multipass image's error keeps falling pass after pass.
TEST(Multipass, KeepsConvergingWhereShirleyFlattensOut) {
  RADIANT_SKIP_UNDER_SANITIZER();
  Scene scene = loadScene(kSpecularBox);
  RayTracer tracer(scene);
  const int size = 24;
  RenderContext plain;
  const Film reference = renderWith(tracer, plain, "path", size, 8192, 99);
  MeshOptions mesh;
  mesh.maxEdgeLength = 0.25;  // coarse: 2 × 2 elements on a wall
  SolverOptions solver;
  solver.solver = "progressive";
  const Solution coarse = meshAndSolve(scene, tracer, mesh, solver);
  RenderContext withSolution;
  withSolution.solution = &coarse;
  const double shirleyFew = test::meanBlockError(renderWith(tracer, withSolution, "shirley", size, 64), reference, 4);
  const double shirleyMany = test::meanBlockError(renderWith(tracer, withSolution, "shirley", size, 512), reference, 4);

  PinholeCamera camera(scene.camera, size, size);
  MultipassOptions options;
  options.samplesPerPixel = 1024;
  options.photonsPerPass = 100000;
  std::vector<double> errors;
  const MultipassSolver solve = progressiveOn(tracer, mesh.maxEdgeLength);
  renderMultipass(tracer, camera, size, size, options, solve,
                  [&](const MultipassPass &pass, const Image &mean, const Image &) {
                    if (pass.index < 3) return;  // the preview and the high-frequency pass read the coarse solution
                    Film film(size, size);
                    for (size_t p = 0; p < film.pixelCount(); ++p)
                      film.add(p, Bands(mean.rgb[3 * p], mean.rgb[3 * p + 1], mean.rgb[3 * p + 2]));
                    errors.push_back(test::meanBlockError(film, reference, 4));
                  });
  ASSERT_GE(errors.size(), 4u);
  // shirley: 8× the samples barely help — bias dominates.
  EXPECT_GT(shirleyMany, 0.6 * shirleyFew);
  // multipass: the last pass is well below shirley's floor and below its own first combined image.
  EXPECT_LT(errors.back(), 0.5 * shirleyMany);
  EXPECT_LT(errors.back(), 0.6 * errors.front());
  std::cout << "block error: shirley 64 spp " << shirleyFew << ", 512 spp " << shirleyMany << "; multipass";
  for (double e : errors) std::cout << " " << e;
  std::cout << "\n";
}

}  // namespace
}  // namespace radiant
