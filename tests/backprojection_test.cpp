// Exact direct light by backprojection (radiosity/backprojection.h), against
// closed forms and against an unbiased count of cosine-distributed rays.
#include "radiosity/backprojection.h"

#include <gtest/gtest.h>

#include "radiosity/form_factor.h"
#include "raytrace/ray_tracer.h"
#include "test_scenes.h"
#include "util/random.h"

using namespace radiant;

namespace {

constexpr double kUnitSquareAtHeightOne = 0.239456;  // F under a unit square's centre, docs/radiosity.md

/// An emitter: the unit square centred over the origin at height 1, facing down (material 0).
Scene emitterOverOrigin() {
  Scene s;
  s.objects.push_back({"test", "test"});
  Material light;
  light.name = "light";
  light.diffuse = Bands(0.0);
  light.emission = Bands(1.0, 2.0, 3.0);
  Material grey;
  grey.name = "grey";
  s.materials = {light, grey};
  s.positions = {{-0.5, -0.5, 1}, {-0.5, 0.5, 1}, {0.5, 0.5, 1}, {0.5, -0.5, 1}};
  test::addQuads(s, {0});
  return s;
}

/// Adds a quad over four new positions (material 1), counter-clockwise as given.
void addQuad(Scene &s, Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  const uint32_t first = static_cast<uint32_t>(s.positions.size());
  s.positions.insert(s.positions.end(), {a, b, c, d});
  Face f;
  f.vertexCount = 4;
  for (uint32_t i = 0; i < 4; ++i) f.vertices[i] = first + i;
  f.material = 1;
  s.addFace(f);
}

void addTriangle(Scene &s, Vec3 a, Vec3 b, Vec3 c) {
  const uint32_t first = static_cast<uint32_t>(s.positions.size());
  s.positions.insert(s.positions.end(), {a, b, c});
  Face f;
  f.vertexCount = 3;
  for (uint32_t i = 0; i < 3; ++i) f.vertices[i] = first + i;
  f.material = 1;
  s.addFace(f);
}

/// F(x → emitter 0 with visibility) by stratified sampling of the emitter
/// (the unit square at height 1), one shadow ray per stratum: converges as
/// N^(-3/4) at shadow boundaries, so 1000² strata give about 10⁻⁵.
double areaSampledFormFactor(const Scene &scene, const Vec3 &x, const Vec3 &n, int strata) {
  RayTracer tracer(scene);
  Pcg32 rng(12345, 678);
  double sum = 0;
  for (int i = 0; i < strata; ++i)
    for (int j = 0; j < strata; ++j) {
      const Vec3 y{-0.5 + (i + rng.next()) / strata, -0.5 + (j + rng.next()) / strata, 1};
      const Vec3 d = y - x;
      const double r = length(d), cosX = dot(d, n) / r, cosY = d.z / r;
      if (cosX > 0 && cosY > 0 && tracer.visible(x, n, y, {0, 0, -1})) sum += cosX * cosY / (kPi * r * r);
    }
  return sum / (double(strata) * strata);
}

}  // namespace

TEST(Backprojection, UnoccludedIsTheContourIntegral) {
  Scene s = emitterOverOrigin();
  DirectIrradiance direct(s);
  ASSERT_EQ(direct.emitters().size(), 1u);
  EXPECT_NEAR(direct.visibleFormFactor({0, 0, 0}, {0, 0, 1}, 0), kUnitSquareAtHeightOne, 1e-6);
  EXPECT_NEAR(direct.unoccludedFormFactor({0, 0, 0}, {0, 0, 1}, 0), kUnitSquareAtHeightOne, 1e-6);
  // Irradiance = π L_e F per band.
  Bands h = direct.irradiance({0, 0, 0}, {0, 0, 1});
  for (int b = 0; b < kBandCount; ++b) EXPECT_NEAR(h[b], kPi * (b + 1) * kUnitSquareAtHeightOne, 1e-5);
  // Behind the emitter's front, or facing away: nothing.
  EXPECT_EQ(direct.visibleFormFactor({0, 0, 2}, {0, 0, -1}, 0), 0.0);
  EXPECT_EQ(direct.visibleFormFactor({0, 0, 0}, {0, 0, -1}, 0), 0.0);
}

TEST(Backprojection, AnOccluderHidingHalfTheEmitterHalvesTheFormFactor) {
  Scene s = emitterOverOrigin();
  // At height 0.5, x ∈ [0, 1] projects from the origin onto x ∈ [0, 2] at height 1: the emitter's half x > 0.
  addQuad(s, {0, -1, 0.5}, {1, -1, 0.5}, {1, 1, 0.5}, {0, 1, 0.5});
  DirectIrradiance direct(s);
  EXPECT_NEAR(direct.visibleFormFactor({0, 0, 0}, {0, 0, 1}, 0), kUnitSquareAtHeightOne / 2, 1e-6);
  // Both sides of the occluder block: flipping its winding changes nothing.
  Scene flipped = emitterOverOrigin();
  addQuad(flipped, {0, 1, 0.5}, {1, 1, 0.5}, {1, -1, 0.5}, {0, -1, 0.5});
  DirectIrradiance direct2(flipped);
  EXPECT_NEAR(direct2.visibleFormFactor({0, 0, 0}, {0, 0, 1}, 0), kUnitSquareAtHeightOne / 2, 1e-6);
}

TEST(Backprojection, OccludersBeyondTheEmitterOrBehindThePointDoNothing) {
  Scene s = emitterOverOrigin();
  addQuad(s, {-2, -2, 1.5}, {2, -2, 1.5}, {2, 2, 1.5}, {-2, 2, 1.5});      // above the emitter
  addQuad(s, {-2, -2, -0.5}, {2, -2, -0.5}, {2, 2, -0.5}, {-2, 2, -0.5});  // below the point
  addQuad(s, {3, -2, 0}, {3, 2, 0}, {3, 2, 1}, {3, -2, 1});                // beside the shaft
  DirectIrradiance direct(s);
  EXPECT_NEAR(direct.visibleFormFactor({0, 0, 0}, {0, 0, 1}, 0), kUnitSquareAtHeightOne, 1e-6);
}

TEST(Backprojection, FullyHiddenAndOverlappingOccluders) {
  Scene s = emitterOverOrigin();
  // Two overlapping occluders that between them hide everything.
  addQuad(s, {-1, -1, 0.5}, {0.2, -1, 0.5}, {0.2, 1, 0.5}, {-1, 1, 0.5});
  addQuad(s, {-0.2, -1, 0.4}, {1, -1, 0.4}, {1, 1, 0.4}, {-0.2, 1, 0.4});
  DirectIrradiance direct(s);
  EXPECT_EQ(direct.visibleFormFactor({0, 0, 0}, {0, 0, 1}, 0), 0.0);
  EXPECT_EQ(direct.irradiance({0.1, 0.1, 0}, {0, 0, 1}).max(), 0.0);
}

TEST(Backprojection, AWallThroughThePointHidesWhatIsBehindIt) {
  Scene s = emitterOverOrigin();
  // A vertical wall in the plane x = 0 standing on the receiver's plane: a point at its foot
  // sees the half x < 0 of the emitter only when it is on that side (normal tilted away).
  addQuad(s, {0, -2, 0}, {0, 2, 0}, {0, 2, 0.9}, {0, -2, 0.9});
  DirectIrradiance direct(s);
  const double f = direct.visibleFormFactor({-1e-4, 0, 0}, {0, 0, 1}, 0);
  EXPECT_NEAR(f,
              formFactorPointToPolygon({-1e-4, 0, 0}, {0, 0, 1},
                                       std::vector<Vec3>{{-0.5, -0.5, 1}, {-0.5, 0.5, 1}, {0, 0.5, 1}, {0, -0.5, 1}}),
              1e-4);
  // On the other side it sees the half x > 0, and the two halves make the whole.
  EXPECT_NEAR(f + direct.visibleFormFactor({1e-4, 0, 0}, {0, 0, 1}, 0), kUnitSquareAtHeightOne, 1e-4);
}

TEST(Backprojection, AgreesWithShadowRaysAmongRandomOccluders) {
  // Random triangles between a tilted receiver and the emitter: the exact
  // visible factor against shadow rays to 10⁶ strata of the emitter.
  Scene s = emitterOverOrigin();
  Pcg32 rng(7, 11);
  for (int k = 0; k < 12; ++k) {
    Vec3 c{rng.next() - 0.5, rng.next() - 0.5, 0.2 + 0.6 * rng.next()};
    auto jitter = [&] { return Vec3{0.6 * (rng.next() - 0.5), 0.6 * (rng.next() - 0.5), 0.3 * (rng.next() - 0.5)}; };
    addTriangle(s, c + jitter(), c + jitter(), c + jitter());
  }
  DirectIrradiance direct(s);
  for (Vec3 x : {Vec3{0, 0, 0}, Vec3{0.3, -0.2, 0.05}}) {
    const Vec3 n = normalize(Vec3{0.2, -0.1, 1});
    const double exact = direct.visibleFormFactor(x, n, 0);
    EXPECT_LT(exact, direct.unoccludedFormFactor(x, n, 0) * 0.85)
        << "the occluders must matter for the test to mean anything";
    EXPECT_NEAR(exact, areaSampledFormFactor(s, x, n, 1000), 1e-4);
  }
}
