// Rough glass (MaterialKind::Dielectric with transmissionRoughness > 0):
// microfacet reflection and refraction, GGX D and Smith G (Walter, Marschner,
// Li & Torrance 2007). sample() against pdf() by chi-square on both sides of
// the surface, energy and the smooth limit, reciprocity, the path tracer's
// NEE + MIS through a pane against a quadrature of f, and the loaders.
// Every tolerance is 5 standard errors of the test's own samples, or round-off.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>

#include "chi_square.h"
#include "raytrace/ray_tracer.h"
#include "render/bsdf.h"
#include "render/registry.h"
#include "render/renderer.h"
#include "render/sampler.h"
#include "scene/load_scene.h"
#include "util/error.h"
#include "util/random.h"
#include "util/sampling.h"

namespace radiant {
namespace {

using test::kPhiBins;
using test::kThetaBins;
using test::sphereBin;
constexpr int kChiSquareTests = 5;

Material roughGlass(double alpha, double ior, const Bands &transmittance = Bands(1.0)) {
  Material m;
  m.name = "rough glass";
  m.kind = MaterialKind::Dielectric;
  m.diffuse = Bands(0.0);
  m.specular = transmittance;
  m.ior = ior;
  m.transmissionRoughness = alpha;
  return m;
}

struct Case {
  Vec3 wo;  ///< the normal is +z: wo.z < 0 looks from inside the glass
  double alpha, ior;
};

std::string describe(const Case &c) {
  std::ostringstream s;
  s << "wo (" << c.wo.x << ", " << c.wo.y << ", " << c.wo.z << "), α " << c.alpha << ", ior " << c.ior;
  return s.str();
}

// Outside at normal and grazing incidence, inside below and beyond the
// critical angle (sin θ = 0.77 > 1/1.5: the smooth surface reflects all).
const Case kCases[kChiSquareTests] = {
    {normalize(Vec3{0.3, -0.2, 0.9}), 0.3, 1.5},   {normalize(Vec3{0.9, 0.0, 0.2}), 0.6, 1.5},
    {normalize(Vec3{0.1, 0.2, -0.95}), 0.2, 1.33}, {normalize(Vec3{0.6, 0.1, -0.5}), 0.4, 1.5},
    {normalize(Vec3{-0.5, 0.4, 0.6}), 1.0, 2.4},
};

/// sample() draws the density pdf() claims, over both hemispheres; its
/// weight is evaluate()·|cos|/pdf(), finite, per band.
TEST(RoughGlass, SamplingMatchesPdfOnBothSides) {
  const Vec3 n{0, 0, 1};
  for (const Case &c : kCases) {
    SCOPED_TRACE(describe(c));
    const Material m = roughGlass(c.alpha, c.ior, Bands(0.9, 0.6, 0.3));
    ASSERT_FALSE(m.isDelta());
    Bsdf bsdf(m, n, n, c.wo);
    ASSERT_FALSE(bsdf.isDelta());
    constexpr int kSamples = 400000;
    std::vector<double> observed(kThetaBins * kPhiBins + 1, 0.0);
    Pcg32 rng(2024, 7);
    int transmitted = 0, badWeights = 0;
    for (int k = 0; k < kSamples; ++k) {
      BsdfSample s;
      const double a = rng.next(), b = rng.next(), d = rng.next();
      if (!bsdf.sample(a, b, d, s)) {
        observed.back() += 1;
        continue;
      }
      observed[sphereBin(s.wi)] += 1;
      transmitted += s.isTransmission;
      EXPECT_FALSE(s.isDelta);
      EXPECT_EQ(s.isTransmission, (s.wi.z < 0) != (c.wo.z < 0));
      const Bands expected = bsdf.evaluate(s.wi) * (std::abs(s.wi.z) / bsdf.pdf(s.wi));
      for (int i = 0; i < kBandCount; ++i)
        if (!std::isfinite(s.weight[i]) || std::abs(s.weight[i] - expected[i]) > 1e-9 * (1 + expected[i])) ++badWeights;
    }
    EXPECT_EQ(badWeights, 0);
    EXPECT_GT(transmitted, kSamples / 20) << "both sides are tested";
    std::vector<double> expected = test::integratePdfOverSphereBins([&](const Vec3 &w) { return bsdf.pdf(w); }, 16);
    double total = 0;
    for (double &e : expected) total += e, e *= kSamples;
    expected.push_back(std::max(0.0, 1 - total) * kSamples);
    const test::ChiSquareResult r = test::chiSquare(observed, expected);
    EXPECT_GT(r.pValue, test::significanceLevel(kChiSquareTests))
        << "chi² = " << r.statistic << " with " << r.degreesOfFreedom << " degrees of freedom; ∫pdf = " << total;
  }
}

struct WeightMean {
  double radiance = 0, power = 0;            ///< means of the weight, and of the weight with (η_far/η_near)² undone
  double radianceError = 0, powerError = 0;  ///< their standard errors
};

/// Mean sample weight of a white glass at wo (normal +z): the albedo for
/// radiance, and for power (as caustic_photons.cpp undoes the η² on refraction).
WeightMean meanWeight(const Material &m, const Vec3 &wo, int samples) {
  const Vec3 n{0, 0, 1};
  Bsdf bsdf(m, n, n, wo);
  const double eta = wo.z > 0 ? m.ior : 1 / m.ior;
  Pcg32 rng(99, 3);
  double sum = 0, sum2 = 0, sumPower = 0, sumPower2 = 0;
  for (int k = 0; k < samples; ++k) {
    BsdfSample s;
    const double a = rng.next(), b = rng.next(), d = rng.next();
    if (!bsdf.sample(a, b, d, s)) continue;
    const double w = s.weight[0], p = s.isTransmission ? w * eta * eta : w;
    sum += w, sum2 += w * w, sumPower += p, sumPower2 += p * p;
  }
  WeightMean r;
  const double n2 = double(samples);
  r.radiance = sum / n2, r.power = sumPower / n2;
  r.radianceError = std::sqrt(std::max(0.0, sum2 / n2 - r.radiance * r.radiance) / n2);
  r.powerError = std::sqrt(std::max(0.0, sumPower2 / n2 - r.power * r.power) / n2);
  return r;
}

/// A white rough glass scatters at most the power it receives (single
/// scattering with Smith's G loses some); as α → 0 its albedo for radiance
/// tends to the smooth glass's F + (1 − F)/η² at the same wo.
TEST(RoughGlass, EnergyIsConservedAndTheSmoothLimitIsSmoothGlass) {
  for (const Case &c : kCases) {
    SCOPED_TRACE(describe(c));
    for (double alpha : {0.05, 0.3, 1.0}) {
      const WeightMean w = meanWeight(roughGlass(alpha, c.ior), c.wo, 200000);
      EXPECT_LE(w.power, 1 + 5 * w.powerError) << "α " << alpha;
    }
    Material smooth = roughGlass(0, c.ior);
    ASSERT_TRUE(smooth.isDelta());
    const double eta = c.wo.z > 0 ? c.ior : 1 / c.ior;
    const double f = fresnelDielectric(std::abs(c.wo.z), eta);
    const double smoothAlbedo = f + (1 - f) / (eta * eta);
    const WeightMean w = meanWeight(roughGlass(1e-3, c.ior), c.wo, 1000000);
    EXPECT_NEAR(w.radiance, smoothAlbedo, 5 * w.radianceError + 1e-12);
  }
}

/// f(wo, wi)/η_o² = f(wi, wo)/η_i², η_o the index on wo's side (radiance BTDF);
/// for reflection plainly f(wo, wi) = f(wi, wo).
TEST(RoughGlass, Reciprocity) {
  const Vec3 n{0, 0, 1};
  const Material m = roughGlass(0.35, 1.5, Bands(0.8, 0.7, 0.6));
  Pcg32 rng(5, 5);
  int nonzeroReflections = 0, nonzeroTransmissions = 0;
  for (int k = 0; k < 2000; ++k) {
    auto direction = [&] {
      const double z = 2 * rng.next() - 1, phi = 2 * kPi * rng.next(), r = std::sqrt(std::max(0.0, 1 - z * z));
      return Vec3{r * std::cos(phi), r * std::sin(phi), z};
    };
    const Vec3 wo = direction(), wi = direction();
    if (std::abs(wo.z) < 1e-3 || std::abs(wi.z) < 1e-3) continue;
    const Bands forward = Bsdf(m, n, n, wo).evaluate(wi), backward = Bsdf(m, n, n, wi).evaluate(wo);
    const double etaO = wo.z > 0 ? 1.0 : m.ior, etaI = wi.z > 0 ? 1.0 : m.ior;
    const bool transmission = (wo.z > 0) != (wi.z > 0);
    for (int b = 0; b < kBandCount; ++b) {
      const double a = forward[b] / (etaO * etaO), c = backward[b] / (etaI * etaI);
      EXPECT_NEAR(a, c, 1e-10 * std::max(a, c) + 1e-14) << "transmission " << transmission;
    }
    (transmission ? nonzeroTransmissions : nonzeroReflections) += forward[0] > 0;
  }
  EXPECT_GT(nonzeroReflections, 100);
  EXPECT_GT(nonzeroTransmissions, 100);
}

/// A rough pane (the z = 0 plane's quad, front up or down) over an emitter
/// of radiance 1 facing it at z = −1, nothing else: what the path tracer
/// sees at a pane point is ∫ f L |cos θi| dω over the emitter, light sampling
/// and BSDF sampling weighed by MIS, against a midpoint quadrature of
/// evaluate() over the emitter's area.
void expectPathMatchesQuadrature(double alpha, double ior, bool frontUp, const Vec3 &eye, const Vec3 &target) {
  SCOPED_TRACE("α " + std::to_string(alpha) + ", ior " + std::to_string(ior) +
               (frontUp ? ", seen from outside" : ", seen from inside"));
  Scene scene;
  Material black;
  black.name = "lamp";
  black.diffuse = Bands(0.0);
  black.emission = Bands(1.0);
  scene.materials = {black, roughGlass(alpha, ior)};
  const double pane = 3, lamp = 0.6;
  for (const Vec3 &p : {Vec3{-pane, -pane, 0}, Vec3{pane, -pane, 0}, Vec3{pane, pane, 0}, Vec3{-pane, pane, 0}})
    scene.positions.push_back(p);
  for (const Vec3 &p : {Vec3{-lamp, -lamp, -1}, Vec3{lamp, -lamp, -1}, Vec3{lamp, lamp, -1}, Vec3{-lamp, lamp, -1}})
    scene.positions.push_back(p);
  Face glass;
  glass.vertexCount = 4;
  for (uint32_t i = 0; i < 4; ++i) glass.vertices[i] = frontUp ? i : 3 - i;
  glass.material = 1;
  Face emitter;
  emitter.vertexCount = 4;
  for (uint32_t i = 0; i < 4; ++i) emitter.vertices[i] = 4 + i;
  emitter.material = 0;
  ASSERT_TRUE(scene.addFace(glass));
  ASSERT_TRUE(scene.addFace(emitter));
  ASSERT_NEAR(scene.faceNormal(scene.faces[0]).z, frontUp ? 1 : -1, 1e-12);
  ASSERT_NEAR(scene.faceNormal(scene.faces[1]).z, 1, 1e-12);

  const Vec3 direction = normalize(target - eye), normal = scene.faceNormal(scene.faces[0]);
  // The expected value: f(wo, wi) L cos θi cos θe / r² over the emitter.
  Bsdf bsdf(scene.materials[1], normal, normal, -direction);
  constexpr int kCells = 800;
  const double h = 2 * lamp / kCells;
  double expected = 0;
  for (int i = 0; i < kCells; ++i)
    for (int j = 0; j < kCells; ++j) {
      const Vec3 y{-lamp + (i + 0.5) * h, -lamp + (j + 0.5) * h, -1};
      const Vec3 d = y - target;
      const double r2 = dot(d, d);
      const Vec3 wi = d / std::sqrt(r2);
      expected += bsdf.evaluate(wi)[0] * std::abs(wi.z) * -wi.z / r2 * h * h;
    }

  RayTracer tracer(scene);
  auto renderer = createRenderer("path", tracer, RenderContext{});
  Sampler rng(Pcg32(17, 4));
  constexpr int kSamples = 200000;
  double sum = 0, sum2 = 0;
  for (int k = 0; k < kSamples; ++k) {
    const double L = renderer->radiance({eye, direction}, rng)[0];
    ASSERT_TRUE(std::isfinite(L));
    sum += L, sum2 += L * L;
  }
  const double mean = sum / kSamples, error = std::sqrt(std::max(0.0, sum2 / kSamples - mean * mean) / kSamples);
  EXPECT_GT(expected, 0.01);
  EXPECT_GT(error, 0.0) << "no variance: the test could not fail";
  EXPECT_NEAR(mean, expected, 5 * error) << "quadrature " << expected << ", path " << mean << " ± " << error;
  std::cout << "[ rough pane ] α " << alpha << " ior " << ior << (frontUp ? " outside" : " inside") << ": path " << mean
            << " ± " << error << ", quadrature " << expected << "\n";
}

TEST(RoughGlass, PathTracerThroughAPaneMatchesTheIntegralOfF) {
  // Near normal incidence and at 40°, from outside (η = ior) and inside (η = 1/ior, the radiance gains ior²).
  expectPathMatchesQuadrature(0.3, 1.5, true, {-0.3, 0.2, 1}, {0.1, 0, 0});
  expectPathMatchesQuadrature(0.05, 1.5, true, {0.05, 0.0, 1}, {0.0, 0.05, 0});
  expectPathMatchesQuadrature(0.5, 1.5, false, {-0.7, 0.3, 1}, {0.1, -0.1, 0});
}

/// Roughness 0 keeps smooth glass exactly: a delta lobe with the same sample as before.
TEST(RoughGlass, ZeroRoughnessAndIndexOneStaySmooth) {
  EXPECT_TRUE(roughGlass(0, 1.5).isDelta());
  EXPECT_TRUE(roughGlass(0.3, 1.0).isDelta()) << "an index of 1 bends no ray";
  EXPECT_FALSE(roughGlass(0.3, 1.5).isDelta());
  EXPECT_TRUE(roughGlass(0.3, 1.5).isSpecular());
  Material def;
  def.kind = MaterialKind::Dielectric;
  EXPECT_EQ(def.transmissionRoughness, 0.0);
  EXPECT_TRUE(def.isDelta());
}

std::string temporaryFile(const std::string &name, const std::string &text) {
  static std::atomic<int> counter{0};
  const auto dir = std::filesystem::temp_directory_path() /
                   ("radiant-rough-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  std::filesystem::create_directories(dir);
  const auto file = dir / name;
  std::ofstream(file, std::ios::binary) << text;
  return file.string();
}

std::string jsonScene(const std::string &glass) {
  return R"({"units": "metres", "image": {"width": 16, "height": 16},
  "camera": {"eye": [0.5, 0.5, 3], "target": [0.5, 0.5, 0], "up": [0, 1, 0], "fov": 40},
  "materials": {"lamp": {"reflectance": 0.5, "emission": 1}, "glass": )" +
         glass + R"(},
  "objects": [{"type": "quad", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "material": "lamp"},
              {"type": "quad", "vertices": [[0,0,1],[1,0,1],[1,1,1],[0,1,1]], "material": "glass"}]})";
}

TEST(RoughGlass, JsonRoughness) {
  Scene s = parseSceneJson(jsonScene(R"({"type": "dielectric", "ior": 1.5, "roughness": 0.25})"), "s.json");
  ASSERT_EQ(s.materials.size(), 2u);
  const Material &glass = s.materials[1].kind == MaterialKind::Dielectric ? s.materials[1] : s.materials[0];
  EXPECT_EQ(glass.transmissionRoughness, 0.25);
  EXPECT_FALSE(glass.isDelta());
  Scene smooth = parseSceneJson(jsonScene(R"({"type": "dielectric"})"), "s.json");
  for (const Material &m : smooth.materials) {
    if (m.kind == MaterialKind::Dielectric) {
      EXPECT_TRUE(m.isDelta());
    }
  }
  for (const char *bad : {"-0.1", "1.5"}) {
    try {
      parseSceneJson(jsonScene(std::string(R"({"type": "dielectric", "roughness": )") + bad + "}"), "s.json");
      ADD_FAILURE() << "roughness " << bad << " was accepted";
    } catch (const InputError &e) {
      EXPECT_NE(std::string(e.what()).find("expected 0 (smooth glass) or α in (0, 1]"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("roughness"), std::string::npos) << e.what();
    }
  }
}

TEST(RoughGlass, MgfTsRoughness) {
  const std::string square = "v a =\n p 0 0 0\nv b =\n p 1 0 0\nv c =\n p 1 1 0\nv d =\n p 0 1 0\n";
  const Scene scene = loadScene(temporaryFile(
      "glass.mgf", square +
                       "m rough =\n ir 1.5 0\n ts 0.9 0.2\nf a b c d\nm fine =\n ir 1.5 0\n ts 0.9 0.001\nf a b c d\n"
                       "m sheet =\n ts 0.9 0.2\nf a b c d\n"));
  ASSERT_EQ(scene.materials.size(), 3u);
  EXPECT_EQ(scene.materials[0].transmissionRoughness, 0.2);
  EXPECT_FALSE(scene.materials[0].isDelta());
  EXPECT_EQ(scene.materials[1].transmissionRoughness, 0.01) << "α is clamped to [0.01, 1]";
  EXPECT_TRUE(scene.materials[2].isDelta()) << "no ir: index 1, a thin sheet, bends no ray";
  for (const std::string &w : scene.warnings) EXPECT_EQ(w.find("roughness of ts"), std::string::npos) << w;
}

}  // namespace
}  // namespace radiant
