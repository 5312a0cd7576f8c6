// The reference path tracer against closed-form answers, with tolerances taken
// from the images' own sample variance.
#include <gtest/gtest.h>

#include "raytrace/ray_tracer.h"
#include "render/driver.h"
#include "render/registry.h"
#include "render/renderer.h"
#include "render_helpers.h"
#include "scene/load_scene.h"
#include "test_scenes.h"

namespace radiant {
namespace {

struct ImageEstimate {
  Bands mean;
  Bands standardError;  ///< of the image mean, from per-pixel sample variances
};

Film renderFilm(const Scene &scene, int width, int spp, int threads = 0, uint64_t seed = 1) {
  RayTracer tracer(scene);
  auto renderer = createRenderer("path", tracer, RenderContext{});
  PinholeCamera camera(scene.camera, width, width);
  Film film(width, width);
  DriverOptions options;
  options.samplesPerPixel = spp;
  options.threads = threads;
  options.seed = seed;
  renderImage(camera, *renderer, options, film);
  return film;
}

ImageEstimate estimate(const Film &film) {
  ImageEstimate e;
  Bands variance(0.0);
  for (size_t p = 0; p < film.pixelCount(); ++p) {
    e.mean += film.mean(p);
    variance += film.varianceOfMean(p);
  }
  double n = static_cast<double>(film.pixelCount());
  e.mean = e.mean / n;
  for (int b = 0; b < kBandCount; ++b) e.standardError[b] = std::sqrt(variance[b]) / n;
  return e;
}

/// Asserts the image mean is within 5 standard errors of `expected` in every band
/// (a 5σ band fails by chance about once in 1.7 million runs).
void expectMeanWithinNoise(const Film &film, double expected) {
  ImageEstimate e = estimate(film);
  for (int b = 0; b < kBandCount; ++b) {
    EXPECT_GT(e.standardError[b], 0.0) << "no variance estimate: the test could not fail";
    EXPECT_NEAR(e.mean[b], expected, 5 * e.standardError[b]) << "band " << b;
  }
}

class Furnace : public ::testing::TestWithParam<double> {};

TEST_P(Furnace, RadianceIsEmissionOverOneMinusReflectance) {
  const double E = 1.0, rho = GetParam();
  Scene scene = test::furnace(E, rho);
  Film film = renderFilm(scene, 24, 32);
  if (rho == 0) {
    // Every path ends at the first wall: the estimate is exact and noise-free.
    for (size_t p = 0; p < film.pixelCount(); ++p) EXPECT_DOUBLE_EQ(film.mean(p)[0], E);
  } else {
    expectMeanWithinNoise(film, E / (1 - rho));
  }
}

INSTANTIATE_TEST_SUITE_P(PathTracer, Furnace, ::testing::Values(0.0, 0.3, 0.5, 0.8, 0.9));

/// Lossless specular objects leave an isotropic radiance field unchanged:
/// a perfect mirror and clear glass inside the furnace must not show.
TEST(PathTracer, LosslessSpecularObjectsVanishInTheFurnace) {
  for (MaterialKind kind : {MaterialKind::Mirror, MaterialKind::Dielectric}) {
    Scene scene = test::furnace(1.0, 0.5);
    Material specular;
    specular.kind = kind;
    specular.diffuse = Bands(0.0);
    specular.specular = Bands(1.0);
    specular.ior = 1.5;
    scene.materials.push_back(specular);
    // A closed tetrahedron in front of the camera (outward faces, counter-clockwise from outside).
    uint32_t base = static_cast<uint32_t>(scene.positions.size());
    scene.positions.push_back({0.7, 0.55, 0.6});
    scene.positions.push_back({0.85, 0.6, 0.75});
    scene.positions.push_back({0.7, 0.75, 0.7});
    scene.positions.push_back({0.8, 0.7, 0.55});
    const uint32_t tetra[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    Vec3 centre =
        (scene.positions[base] + scene.positions[base + 1] + scene.positions[base + 2] + scene.positions[base + 3]) / 4;
    for (auto &t : tetra) {
      Face f;
      for (int i = 0; i < 3; ++i) f.vertices[i] = base + t[i];
      f.material = 1;
      Vec3 n = scene.faceNormal(f);
      if (dot(n, scene.positions[f.vertices[0]] - centre) < 0) std::swap(f.vertices[1], f.vertices[2]);
      ASSERT_TRUE(scene.addFace(f));
    }
    Film film = renderFilm(scene, 24, 32);
    SCOPED_TRACE(materialKindName(kind));
    expectMeanWithinNoise(film, 2.0);
  }
}

TEST(PathTracer, EmittersAreOneSided) {
  // A box whose only emitter is the +z wall, facing into the box. From inside it glows;
  // the same wall seen from behind (camera outside the box) is black.
  const int walls[6] = {0, 0, 0, 0, 0, 1};
  Scene scene = test::closedBox(1.0, walls);
  Material black, light;
  black.diffuse = Bands(0.0);
  light.diffuse = Bands(0.0);
  light.emission = Bands(3.0);
  scene.materials = {black, light};
  RayTracer tracer(scene);
  auto renderer = createRenderer("path", tracer, RenderContext{});
  Sampler rng(Pcg32(1, 1));
  Bands inside = renderer->radiance({{0.5, 0.5, 0.5}, {0, 0, 1}}, rng);
  EXPECT_DOUBLE_EQ(inside[0], 3.0);
  Bands behind = renderer->radiance({{0.5, 0.5, 2.0}, {0, 0, -1}}, rng);
  EXPECT_DOUBLE_EQ(behind[0], 0.0);
}

TEST(PathTracer, MirrorShowsTheEmitterScaledByItsReflectance) {
  // Camera looks down −z at a mirror at z = 0; an emitter at z = 1 faces −z... and is behind the camera.
  const int walls[6] = {0, 0, 0, 0, 2, 1};
  Scene scene = test::closedBox(1.0, walls);
  Material black, light, mirror;
  black.diffuse = Bands(0.0);
  light.diffuse = Bands(0.0);
  light.emission = Bands(2.0);
  mirror.kind = MaterialKind::Mirror;
  mirror.specular = Bands(0.7, 0.5, 0.3);
  scene.materials = {black, light, mirror};
  RayTracer tracer(scene);
  auto renderer = createRenderer("path", tracer, RenderContext{});
  Sampler rng(Pcg32(1, 1));
  Bands L = renderer->radiance({{0.5, 0.5, 0.5}, normalize(Vec3{0.1, 0.05, -1})}, rng);
  EXPECT_NEAR(L[0], 1.4, 1e-12);
  EXPECT_NEAR(L[1], 1.0, 1e-12);
  EXPECT_NEAR(L[2], 0.6, 1e-12);
}

/// Form factor from a differential area (point p, normal n) to a polygon:
/// Lambert's contour integral (C&W ch. 4).
double formFactorPointToPolygon(const Vec3 &p, const Vec3 &n, const std::vector<Vec3> &polygon) {
  double sum = 0;
  for (size_t k = 0; k < polygon.size(); ++k) {
    Vec3 r0 = polygon[k] - p, r1 = polygon[(k + 1) % polygon.size()] - p, c = cross(r0, r1);
    double cn = length(c);
    if (cn > 0) sum += std::atan2(cn, dot(r0, r1)) * dot(n, c) / cn;
  }
  return std::abs(sum) / (2 * kPi);
}

TEST(PathTracer, DirectLightOnCornellWallMatchesLambertContourFormula) {
  // With one bounce, a Lambertian point of reflectance ρ under a uniform
  // emitter of radiance L (and nothing in between) has radiance ρ·L·F(point → emitter).
  // The last points sit just below the light's plane, where shadow rays graze it:
  // float round-off there once made the light occlude itself.
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  RayTracer tracer(scene);
  auto renderer = createRenderer("path", tracer, RenderContext{}, test::parameters({{"max-depth", "1"}}));
  const double lightY = 0.5487;
  const std::vector<Vec3> light = {
      {0.343, lightY, 0.227}, {0.343, lightY, 0.332}, {0.213, lightY, 0.332}, {0.213, lightY, 0.227}};
  const Vec3 eye{0.278, 0.273, 0.1};
  for (double y : {0.3, 0.5, 0.545, 0.548}) {
    Vec3 onRightWall{0, y, 0.1};
    Ray ray{eye, normalize(onRightWall - eye)};
    Hit hit;
    ASSERT_TRUE(tracer.intersect(ray, hit));
    const Material &wall = scene.materials[hit.material];
    double F = formFactorPointToPolygon(hit.position, hit.geometricNormal, light);
    const Material *emitter = nullptr;
    for (const Material &m : scene.materials)
      if (m.isEmitter()) emitter = &m;
    ASSERT_NE(emitter, nullptr);
    const int n = 100000;
    Bands sum(0.0), sumSquares(0.0);
    for (int i = 0; i < n; ++i) {
      Sampler rng(sampleGenerator(3, 0, i));
      Bands L = renderer->radiance(ray, rng);
      sum += L;
      sumSquares += L * L;
    }
    for (int b = 0; b < kBandCount; ++b) {
      double mean = sum[b] / n, standardError = std::sqrt((sumSquares[b] / n - mean * mean) / (n - 1));
      double expected = wall.diffuse[b] * emitter->emission[b] * F;
      EXPECT_GT(expected, 0);
      EXPECT_NEAR(mean, expected, 5 * standardError + 1e-12) << "y = " << y << ", band " << b;
    }
  }
}

TEST(PathTracer, SameImageWithOneAndTwoThreads) {
  const int walls[6] = {0, 1, 0, 2, 0, 0};
  Scene scene = test::closedBox(1.0, walls);
  Material white, red, light;
  white.diffuse = Bands(0.7);
  red.diffuse = Bands(0.6, 0.1, 0.1);
  light.diffuse = Bands(0.5);
  light.emission = Bands(5.0);
  scene.materials = {white, red, light};
  scene.camera.eye = {0.5, 0.5, 0.05};
  scene.camera.target = {0.5, 0.5, 1};
  Film one = renderFilm(scene, 32, 8, 1, 42);
  Film two = renderFilm(scene, 32, 8, 2, 42);
  Film otherSeed = renderFilm(scene, 32, 8, 2, 43);
  bool anyDifferentFromOtherSeed = false;
  for (size_t p = 0; p < one.pixelCount(); ++p) {
    for (int b = 0; b < kBandCount; ++b) ASSERT_EQ(one.sum[p][b], two.sum[p][b]) << "pixel " << p;
    anyDifferentFromOtherSeed |= one.sum[p][0] != otherSeed.sum[p][0];
  }
  EXPECT_TRUE(anyDifferentFromOtherSeed);
}

}  // namespace
}  // namespace radiant
