// Irradiance images (render --quantity irradiance): what a lux meter lying on
// the surface seen would read, for false-colour illuminance maps.
#include <gtest/gtest.h>

#include <cmath>

#include "radiosity/form_factor.h"
#include "radiosity/solver.h"
#include "render/driver.h"
#include "render/renderer.h"
#include "render_helpers.h"
#include "test_scenes.h"

namespace radiant {
namespace {

struct PixelEstimate {
  double mean = 0, standardError = 0;
};

/// Renders `scene` at `size`² pixels and returns the green band's mean over
/// the pixels and the standard error of that mean.
PixelEstimate renderIrradiance(const Scene &scene, const std::string &method, int spp, int size,
                               double meshSize = 0.5) {
  RenderContext options;
  options.irradiance = true;
  const Film film = test::solveAndRender(scene, method, options, spp, size, meshSize, 1e-8);
  PixelEstimate e;
  double variance = 0;
  for (size_t p = 0; p < film.pixelCount(); ++p) e.mean += film.mean(p)[1], variance += film.varianceOfMean(p)[1];
  e.mean /= film.pixelCount();
  e.standardError = std::sqrt(variance) / film.pixelCount();
  return e;
}

// The furnace (closed form B = E/(1−ρ)): radiance 2 arrives from every
// direction, so the irradiance is π·2 everywhere, whatever the walls' own
// emission.
TEST(Irradiance, TheFurnaceReceivesPiTimesItsRadiance) {
  Scene scene = test::furnace(1.0, 0.5);
  const double expected = 2 * kPi;
  PixelEstimate path = renderIrradiance(scene, "path", 64, 16);
  EXPECT_NEAR(path.mean, expected, 4 * path.standardError);
  EXPECT_GT(path.standardError, 0);
  // Counting the metered wall's own emission would add π·1: far outside.
  EXPECT_GT(std::abs(path.mean + kPi - expected), 50 * path.standardError);
  for (const char *method : {"flat", "interpolate"}) {
    scene = test::furnace(1.0, 0.5);
    PixelEstimate display = renderIrradiance(scene, method, 1, 16);
    EXPECT_NEAR(display.mean, expected, 1e-6 * expected) << method;  // the converged solution's H = (B − E)/ρ
  }
}

// A white floor under a square light of radiance 1, nothing else: the
// irradiance at the floor's centre is π·L·F(point → light), Lambert's contour
// formula (C&W ch. 4). The camera looks straight down at a tiny patch
// around the centre, whose irradiance varies by less than 1e-4.
TEST(Irradiance, UnderASquareLightItIsTheContourFormula) {
  Scene scene;
  scene.objects.push_back({"floor and light", "test"});
  scene.positions = {{-1, 0, -1},       {-1, 0, 1},       {1, 0, 1},       {1, 0, -1},         // floor, facing +y
                     {-0.2, 0.5, -0.2}, {0.2, 0.5, -0.2}, {0.2, 0.5, 0.2}, {-0.2, 0.5, 0.2}};  // light, facing −y
  Material white, light;
  white.name = "white";
  white.diffuse = Bands(0.7);
  light.name = "light";
  light.diffuse = Bands(0.0);
  light.emission = Bands(1.0);
  scene.materials = {white, light};
  test::addQuads(scene, {0, 1});  // the floor, the lamp
  scene.camera.eye = {0, 0.3, 0};
  scene.camera.target = {0, 0, 0};
  scene.camera.up = {0, 0, 1};
  scene.camera.verticalFovDegrees = 0.5;

  const Vec3 lightPolygon[4] = {scene.positions[4], scene.positions[5], scene.positions[6], scene.positions[7]};
  const double expected = kPi * 1.0 * formFactorPointToPolygon({0, 0, 0}, {0, 1, 0}, lightPolygon);
  PixelEstimate path = renderIrradiance(scene, "path", 256, 4);
  EXPECT_NEAR(path.mean, expected, 4 * path.standardError + 1e-4 * expected);
  // The radiance there is ρ/π times it; an irradiance image is not a radiance image.
  EXPECT_GT(std::abs(path.mean - 0.7 / kPi * expected), 50 * path.standardError);
  // The radiosity solution's irradiance, interpolated: mesh error only (5 cm elements).
  PixelEstimate display = renderIrradiance(scene, "interpolate", 1, 4, 0.05);
  EXPECT_NEAR(display.mean, expected, 0.02 * expected);
  std::cout << "irradiance at the floor centre: exact " << expected << ", path " << path.mean << " ± "
            << path.standardError << ", interpolate " << display.mean << "\n";
}

}  // namespace
}  // namespace radiant
