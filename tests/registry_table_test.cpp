// Every method in the registries against scenes with a closed-form answer: one
// table of expectations with every renderer of rendererRegistry() and every
// solver of solverRegistry() under it, as pbrt-v4's
// cpu/integrators_test.cpp renders GetScenes() × GetIntegrators() and checks
// each image's average. The cases are made from the registries when the tests
// are listed, so a method added to render/registry.cpp or radiosity/solver.cpp
// is run here with no edit to this file.
//
// The scenes are closed enclosures whose walls all emit radiance L_e and
// reflect diffusely with reflectance ρ. Whatever the enclosure's shape, if the
// radiance is L everywhere, every point receives the irradiance πL and reflects
// ρ/π · πL, so L = L_e + ρL: L = L_e/(1−ρ) at every point in every direction
// (the furnace), and the irradiance is πL. The box is six quads meeting at
// 90°, each cut into a grid of elements; the sphere is 32 faces, triangles
// and quads, meeting at 45°.
//
// Tolerances. A renderer's image mean is an average of independent pixel
// estimates, so its standard error σ is √(Σ_p Var(pixel mean))/N from the
// pixels' own sample variances, with samples enough to bring σ near 0.2 % of
// L (renderToStandardError). Each band must lie within 5σ of the closed form
// (a 5σ band fails by chance once in 1.7 million; at 16 spp, over 40 seeds,
// the noisy methods here came no further than 2.6σ), plus, for a method that
// reads a solution, that solution's error bound (solutionErrorFraction), plus
// a method's own discretisation error where it has one by design
// (discretisationBiasFraction). A solver's image is the flat display of its
// solution, whose elements all have the same true value here: their scatter
// s is the solution's error per element (noise for the stochastic solver,
// discretisation for the others), and the image mean, Σ_e w_e B_e with w_e
// the share of the pixels showing element e, has the standard error
// s·√(Σ_e w_e²) if those errors are independent; 5 of those plus the sweeps'
// bound are allowed. A solver whose elements all err one way fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <exception>
#include <functional>
#include <initializer_list>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "io/image.h"
#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"
#include "render/driver.h"
#include "render/multipass.h"
#include "render/registry.h"
#include "render/renderer.h"
#include "test_scenes.h"

namespace radiant {
namespace {

/// An inward-facing UV sphere of radius 1 m around the origin, 8 segments
/// around and 4 from pole to pole: triangles at the poles, planar trapezoids
/// between, every wall emitting `emittedRadiance` and reflecting
/// `reflectance`. 32 faces, so that shirley and kok evaluate the direct light
/// exactly (at most 64 emitters, render/shirley.cpp): with many small emitters
/// sampled by area, the shadow rays that land next to the shading point's
/// own edge make heavy tails, and 16 samples per pixel underestimate the
/// variance (with 80 triangles, over 40 seeds, shirley and rushmeier reached
/// 4.5σ). The camera stands off-centre looking down and across.
Scene sphereInterior(double emittedRadiance, double reflectance) {
  const int segments = 8, rings = segments / 2;
  Scene s;
  s.objects.push_back({"sphere", "test"});
  Material wall;
  wall.name = "wall";
  wall.diffuse = Bands(reflectance);
  wall.emission = Bands(emittedRadiance);
  s.materials.push_back(wall);
  // The poles, then rings 1 … rings − 1 of `segments` vertices each.
  s.positions = {{0, 1, 0}, {0, -1, 0}};
  for (int r = 1; r < rings; ++r)
    for (int k = 0; k < segments; ++k) {
      const double theta = kPi * r / rings, phi = 2 * kPi * k / segments;
      s.positions.push_back({std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)});
    }
  auto ringVertex = [&](int r, int k) { return uint32_t(2 + (r - 1) * segments + k % segments); };
  auto addInward = [&](std::initializer_list<uint32_t> vertices) {
    Face f;
    f.vertexCount = int(vertices.size());
    Vec3 centroid;
    int i = 0;
    for (uint32_t v : vertices) f.vertices[i++] = v, centroid += s.positions[v];
    if (dot(s.faceNormal(f), centroid) > 0) std::reverse(f.vertices, f.vertices + f.vertexCount);
    EXPECT_TRUE(s.addFace(f));
  };
  for (int k = 0; k < segments; ++k) {
    addInward({0, ringVertex(1, k), ringVertex(1, k + 1)});
    addInward({1, ringVertex(rings - 1, k), ringVertex(rings - 1, k + 1)});
    for (int r = 1; r + 1 < rings; ++r)
      addInward({ringVertex(r, k), ringVertex(r + 1, k), ringVertex(r + 1, k + 1), ringVertex(r, k + 1)});
  }
  s.camera.eye = {0.2, 0.1, -0.1};
  s.camera.target = {-0.5, -0.3, 0.6};
  s.camera.up = {0, 1, 0};
  s.camera.verticalFovDegrees = 90;
  return s;
}

struct ClosedFormScene {
  const char *name;
  Scene (*build)(double emittedRadiance, double reflectance);
  double emittedRadiance, reflectance;  ///< of every wall
  double meshSize;                      ///< element edge of the uniform mesh, metres
  double radiance() const { return emittedRadiance / (1 - reflectance); }
};

/// Different L_e and ρ per scene, so that no constant passes both.
const std::vector<ClosedFormScene> &closedFormScenes() {
  static const std::vector<ClosedFormScene> scenes = {
      {"Furnace", &test::furnace, 1.0, 0.5, 0.25},         // L = 2; 6 walls × 16 elements
      {"SphereInterior", &sphereInterior, 0.9, 0.7, 0.7},  // L = 3; 32 faces (edges 0.54–0.77 m), 128 elements
  };
  return scenes;
}

/// Image size (pixels, both sides).
constexpr int kImageSize = 32;
/// Samples per pixel: of the pilot image (renderToStandardError), the fewest
/// and the most a case takes (multipass, under its own driver, takes the fewest).
constexpr int kPilotSamplesPerPixel = 4, kSamplesPerPixel = 16, kMaxSamplesPerPixel = 256;
/// The standard error of the image mean aimed at, as a fraction of L, so
/// that every noisy method is held to about 1 % (5σ).
constexpr double kTargetStandardError = 0.002;
/// Standard errors allowed between an image mean and the closed form.
constexpr double kSigmas = 5;

/// Gauss–Seidel's sweep tolerance for the solution the renderers read.
constexpr double kRendererSolutionTolerance = 1e-9;
/// The sweep tolerance (or unshot fraction) every solver of the table is run to.
constexpr double kSolverTolerance = 1e-4;

/// How far a solution to `tolerance` may be from L_e/(1−ρ) everywhere, as a
/// fraction of it. Two parts, both carried through the reflections by
/// ρ/(1−ρ): form factors are stored as floats, each within 2⁻²⁴ of itself,
/// so a row that sums to 1 (a closed enclosure) sums to 1 ± 2⁻²⁴; and the
/// sweeps stop when a sweep changes B by less than tolerance × the reflected
/// radiosity (Gauss–Seidel, hierarchical) or when less than tolerance of the
/// emitted power is unshot (progressive, stochastic), which leaves at most
/// tolerance × ρ/(1−ρ) of B unsolved.
double solutionErrorFraction(double reflectance, double tolerance) {
  return reflectance / (1 - reflectance) * (std::ldexp(1.0, -24) + tolerance);
}

Solution solveOnUniformMesh(const Scene &scene, const RayTracer &tracer, double meshSize,
                            const SolverOptions &options) {
  MeshOptions mesh;
  mesh.maxEdgeLength = meshSize;
  return meshAndSolve(scene, tracer, mesh, options);
}

/// The solution the renderers read: Gauss–Seidel, whose contour-integral
/// form factors sum to 1 in a closed enclosure, so that its error is
/// solutionErrorFraction's and what is tested is the renderer.
Solution convergedSolution(const Scene &scene, const RayTracer &tracer, double meshSize) {
  SolverOptions options;
  options.solver = "gauss-seidel";
  options.tolerance = kRendererSolutionTolerance;
  return solveOnUniformMesh(scene, tracer, meshSize, options);
}

/// An image's mean per band and the standard error of that mean.
struct ImageMean {
  Bands mean, standardError;
};

ImageMean imageMean(const Film &film) {
  ImageMean m;
  Bands variance(0.0);
  for (size_t p = 0; p < film.pixelCount(); ++p) m.mean += film.mean(p), variance += film.varianceOfMean(p);
  const double n = double(film.pixelCount());
  m.mean = m.mean / n;
  for (int b = 0; b < kBandCount; ++b) m.standardError[b] = std::sqrt(variance[b]) / n;
  return m;
}

/// The same from an image and the variance of each pixel's estimate (multipass's output).
ImageMean imageMean(const Image &mean, const Image &variance) {
  ImageMean m;
  Bands sumOfVariances(0.0);
  const size_t pixels = mean.rgb.size() / 3;
  for (size_t p = 0; p < pixels; ++p)
    for (int b = 0; b < kBandCount; ++b) m.mean[b] += mean.rgb[3 * p + b], sumOfVariances[b] += variance.rgb[3 * p + b];
  for (int b = 0; b < kBandCount; ++b)
    m.mean[b] /= double(pixels), m.standardError[b] = std::sqrt(sumOfVariances[b]) / double(pixels);
  return m;
}

/// Each band of `image` within kSigmas standard errors plus `allowance` of `expected`.
void expectCloseToClosedForm(const ImageMean &image, double expected, double allowance, const std::string &what) {
  for (int b = 0; b < kBandCount; ++b)
    EXPECT_NEAR(image.mean[b], expected, kSigmas * image.standardError[b] + allowance)
        << what << ", band " << b << ": σ " << image.standardError[b] << ", allowance " << allowance;
  std::cout << what << ": mean " << image.mean[1] << " (closed form " << expected << "), σ " << image.standardError[1]
            << ", allowed " << kSigmas * image.standardError[1] + allowance << "\n";
}

/// Renders with as many samples per pixel as bring the image mean's standard
/// error down to kTargetStandardError × `expected` (σ ∝ 1/√spp), within
/// kSamplesPerPixel … kMaxSamplesPerPixel. Two stages, so that when to stop
/// does not depend on the samples tested: a pilot image sets the count, and
/// a fresh image, from other seeds, is the one returned. (Stopping once σ's
/// estimate is low enough would favour images that missed a rare large sample.)
struct RenderedFilm {
  Film film;
  int samplesPerPixel = 0;  ///< asked for (the radiosity displays stop converged pixels sooner)
};
RenderedFilm renderToStandardError(const PinholeCamera &camera, const Renderer &renderer, double expected) {
  DriverOptions driver;
  driver.samplesPerPixel = kPilotSamplesPerPixel;
  Film pilot(kImageSize, kImageSize);
  renderImage(camera, renderer, driver, pilot);
  double worst = 0;
  for (int b = 0; b < kBandCount; ++b) worst = std::max(worst, imageMean(pilot).standardError[b] / expected);
  const double spp = kPilotSamplesPerPixel * std::pow(worst / kTargetStandardError, 2);
  driver.samplesPerPixel = int(std::clamp(std::ceil(spp), double(kSamplesPerPixel), double(kMaxSamplesPerPixel)));
  driver.seed = 2;
  RenderedFilm rendered{Film(kImageSize, kImageSize), driver.samplesPerPixel};
  renderImage(camera, renderer, driver, rendered.film);
  return rendered;
}

std::string testNameOf(std::string name) {
  for (char &c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

// ---------------------------------------------------------------- renderers

enum class Quantity { Radiance, Irradiance };

struct RendererCase {
  std::string method;
  size_t scene;  ///< into closedFormScenes()
  Quantity quantity;
};
/// What gtest prints for a case (instead of its bytes).
void PrintTo(const RendererCase &c, std::ostream *out) {
  *out << c.method << " on " << closedFormScenes()[c.scene].name
       << (c.quantity == Quantity::Irradiance ? ", irradiance" : "");
}

/// Every registry entry × every scene, in radiance and, where the entry
/// declares it (supportsIrradiance), in irradiance.
std::vector<RendererCase> rendererCases() {
  std::vector<RendererCase> cases;
  for (const RendererInfo &info : rendererRegistry())
    for (size_t scene = 0; scene < closedFormScenes().size(); ++scene) {
      cases.push_back({info.name, scene, Quantity::Radiance});
      if (info.supportsIrradiance) cases.push_back({info.name, scene, Quantity::Irradiance});
    }
  return cases;
}

/// A method that owns its loop (RendererInfo::render: multipass), run as the
/// command line runs it. The preview reads an interrupted progressive
/// solution, the later passes the converged one; only the last pass, which
/// combines the later passes' samples, is checked (Multipass.TheFurnaceHoldsInEveryPass checks them all).
ImageMean renderThroughItsOwnLoop(const RendererInfo &method, const RayTracer &tracer, const ClosedFormScene &closed,
                                  const RenderContext &context) {
  PinholeCamera camera(tracer.scene().camera, kImageSize, kImageSize);
  ImageJob job{tracer, camera, kImageSize, kImageSize};
  job.samplesPerPixel = kSamplesPerPixel;
  job.pixelAngle = context.pixelSpreadAngle;
  job.solve = [&](int maxShots) {
    if (maxShots == 0) return convergedSolution(tracer.scene(), tracer, closed.meshSize);
    SolverOptions options;
    options.solver = "progressive";
    options.maxIterations = maxShots;
    return solveOnUniformMesh(tracer.scene(), tracer, closed.meshSize, options);
  };
  ImageMean last;
  job.output = [&](int, const std::string &, const Image &mean, const Image &variance) {
    last = imageMean(mean, variance);
  };
  method.render(job, methodParameters(method, {}));
  return last;
}

/// Methods whose image differs from the closed form by design, beyond the
/// solution's error, with the most allowed, as a fraction of L. A method not
/// listed is held to the closed form.
///
/// kok removes the selected sources' share of the indirect light per element,
/// computed at the element's centre, and interpolates what is left, while its
/// shadow rays add that share back at the pixel's own point (docs/two-pass.md,
/// "kok"): the image is off by the error of interpolating the share, which
/// falls as the elements shrink. Measured at 512 spp: −0.07 % in the box
/// (0.25 m elements), −0.25 % in the sphere (0.7 m); in a sphere of 48
/// triangles, −0.12 %, −0.03 % and −0.01 % with 0.5, 0.25 and 0.125 m
/// elements. Allowed: twice the largest, 0.5 %.
const std::map<std::string, double> &discretisationBiasFraction() {
  static const std::map<std::string, double> bias = {{"kok", 0.005}};
  return bias;
}

class EveryRenderer : public ::testing::TestWithParam<RendererCase> {};

TEST_P(EveryRenderer, ImageMeanIsTheClosedForm) {
  const RendererCase &c = GetParam();
  const ClosedFormScene &closed = closedFormScenes()[c.scene];
  const Scene scene = closed.build(closed.emittedRadiance, closed.reflectance);
  RayTracer tracer(scene);
  const bool irradiance = c.quantity == Quantity::Irradiance;
  const double expected = (irradiance ? kPi : 1.0) * closed.radiance();

  RenderContext options;
  options.irradiance = irradiance;
  Solution solution;
  double allowance = 0;
  if (findRenderer(c.method).needsSolution) {
    solution = convergedSolution(scene, tracer, closed.meshSize);
    options.solution = &solution;
    allowance = expected * solutionErrorFraction(closed.reflectance, kRendererSolutionTolerance);
  }
  if (const auto bias = discretisationBiasFraction().find(c.method); bias != discretisationBiasFraction().end())
    allowance += expected * bias->second;
  const RendererInfo &method = findRenderer(c.method);
  ASSERT_TRUE((method.create != nullptr) != (method.render != nullptr))
      << c.method << ": an entry is either a ray-level method (create) or owns its loop (render)";
  if (method.render) {
    expectCloseToClosedForm(renderThroughItsOwnLoop(method, tracer, closed, options), expected, allowance,
                            std::string(closed.name) + ", " + c.method);
    return;
  }
  std::unique_ptr<Renderer> renderer = createRenderer(c.method, tracer, options);
  PinholeCamera camera(scene.camera, kImageSize, kImageSize);
  const RenderedFilm rendered = renderToStandardError(camera, *renderer, expected);
  expectCloseToClosedForm(imageMean(rendered.film), expected, allowance,
                          std::string(closed.name) + ", " + c.method + (irradiance ? " (irradiance)" : "") + ", " +
                              std::to_string(rendered.samplesPerPixel) + " spp");
}

INSTANTIATE_TEST_SUITE_P(RegistryTable, EveryRenderer, ::testing::ValuesIn(rendererCases()),
                         [](const ::testing::TestParamInfo<RendererCase> &info) {
                           return closedFormScenes()[info.param.scene].name + std::string("_") +
                                  testNameOf(info.param.method) +
                                  (info.param.quantity == Quantity::Irradiance ? "_irradiance" : "");
                         });

// ------------------------------------------------------------------ solvers

struct SolverCase {
  std::string solver;
  size_t scene;
};
void PrintTo(const SolverCase &c, std::ostream *out) {
  *out << c.solver << " on " << closedFormScenes()[c.scene].name;
}

std::vector<SolverCase> solverCases() {
  std::vector<SolverCase> cases;
  for (const SolverInfo &info : solverRegistry())
    for (size_t scene = 0; scene < closedFormScenes().size(); ++scene) cases.push_back({info.name, scene});
  return cases;
}

/// Σ_e w_e², w_e the share of the image's pixels whose centre ray shows element e.
double sumOfSquaredPixelShares(const Scene &scene, const RayTracer &tracer, const Solution &solution) {
  PinholeCamera camera(scene.camera, kImageSize, kImageSize);
  std::map<uint32_t, int> pixelsPerElement;
  for (int y = 0; y < kImageSize; ++y)
    for (int x = 0; x < kImageSize; ++x) {
      Hit hit;
      if (tracer.intersect(camera.generateRay(x + 0.5, y + 0.5), hit))
        ++pixelsPerElement[solution.mesh.locate(hit.face, hit.position).element];
    }
  double sum = 0;
  for (const auto &[element, pixels] : pixelsPerElement) sum += std::pow(pixels / double(kImageSize * kImageSize), 2);
  return sum;
}

class EverySolver : public ::testing::TestWithParam<SolverCase> {};

TEST_P(EverySolver, FlatImageMeanIsTheClosedForm) {
  const SolverCase &c = GetParam();
  const ClosedFormScene &closed = closedFormScenes()[c.scene];
  const Scene scene = closed.build(closed.emittedRadiance, closed.reflectance);
  RayTracer tracer(scene);
  // Every solver is asked for the same: sweeps to kSolverTolerance; the
  // solvers that refine by themselves no finer than half the uniform mesh's
  // elements (hierarchical-exact would otherwise take seconds here); and
  // 16 times the default rays per element, so that the stochastic solver's
  // noise (1/√rays) leaves the test some power.
  SolverOptions options;
  options.solver = c.solver;
  options.tolerance = kSolverTolerance;
  options.directMinimumEdge = options.linkMinimumEdge = closed.meshSize / 2;
  options.raysPerElement = 16 * SolverOptions{}.raysPerElement;
  const Solution solution = solveOnUniformMesh(scene, tracer, closed.meshSize, options);
  ASSERT_GT(solution.elementCount(), 1u);

  // The scatter of the elements' radiances about their mean (ambient included, as flat shows them).
  double sum = 0, sumOfSquares = 0;
  for (uint32_t e = 0; e < solution.elementCount(); ++e) {
    const double radiance = solution.displayRadiosity(e)[1] / kPi;
    sum += radiance, sumOfSquares += radiance * radiance;
  }
  const double n = double(solution.elementCount());
  const double scatter = std::sqrt(std::max(0.0, (sumOfSquares - sum * sum / n) / (n - 1)));
  const double solutionError = scatter * std::sqrt(sumOfSquaredPixelShares(scene, tracer, solution));

  RenderContext rendererOptions;
  rendererOptions.solution = &solution;
  PinholeCamera camera(scene.camera, kImageSize, kImageSize);
  Film film(kImageSize, kImageSize);
  DriverOptions driver;
  driver.samplesPerPixel = kSamplesPerPixel;
  renderImage(camera, *createRenderer("flat", tracer, rendererOptions), driver, film);
  const double expected = closed.radiance();
  expectCloseToClosedForm(
      imageMean(film), expected,
      kSigmas * solutionError + expected * solutionErrorFraction(closed.reflectance, kSolverTolerance),
      std::string(closed.name) + ", solver " + c.solver + " (" + std::to_string(solution.elementCount()) +
          " elements, scatter " + std::to_string(scatter) + ")");
}

INSTANTIATE_TEST_SUITE_P(RegistryTable, EverySolver, ::testing::ValuesIn(solverCases()),
                         [](const ::testing::TestParamInfo<SolverCase> &info) {
                           return closedFormScenes()[info.param.scene].name + std::string("_") +
                                  testNameOf(info.param.solver);
                         });

}  // namespace
}  // namespace radiant
