// Chi-square goodness-of-fit tests: every sampling routine draws the density it claims.
#include "util/sampling.h"

#include <gtest/gtest.h>

#include <functional>

#include "chi_square.h"
#include "render/bsdf.h"
#include "render/light_sampler.h"
#include "util/random.h"

namespace radiant {
namespace {

using test::kPhiBins;
using test::kThetaBins;
using test::sphereBin;
constexpr int kTestsInThisFile = 9;

/// Draws `n` directions (nullopt when the sampler rejects) and tests them against `pdf`;
/// rejections form one more bin whose expected share is 1 − ∫pdf.
void expectDirectionsFollowPdf(const std::function<bool(Pcg32 &, Vec3 &)> &sampler,
                               const std::function<double(const Vec3 &)> &pdf, int n = 400000) {
  std::vector<double> observed(kThetaBins * kPhiBins + 1, 0.0);
  Pcg32 rng(12345, 678);
  for (int k = 0; k < n; ++k) {
    Vec3 w;
    if (sampler(rng, w))
      observed[sphereBin(w)] += 1;
    else
      observed.back() += 1;
  }
  std::vector<double> expected = test::integratePdfOverSphereBins(pdf, 12);
  double total = 0;
  for (double &e : expected) {
    total += e;
    e *= n;
  }
  expected.push_back(std::max(0.0, 1 - total) * n);
  test::ChiSquareResult r = test::chiSquare(observed, expected);
  EXPECT_GT(r.pValue, test::significanceLevel(kTestsInThisFile))
      << "chi² = " << r.statistic << " with " << r.degreesOfFreedom << " degrees of freedom; ∫pdf = " << total;
}

TEST(Sampling, CosineHemisphereMatchesItsDensity) {
  expectDirectionsFollowPdf(
      [](Pcg32 &rng, Vec3 &w) {
        double u1 = rng.next(), u2 = rng.next();
        w = sampleCosineHemisphere(u1, u2);
        return true;
      },
      [](const Vec3 &w) { return cosineHemispherePdf(w.z); });
}

/// A BSDF's sample() against its own pdf(), for a fixed outgoing direction.
void expectBsdfSamplingMatchesPdf(const Material &material, const Vec3 &wo) {
  const Vec3 n{0, 0, 1};
  Bsdf bsdf(material, n, n, wo);
  expectDirectionsFollowPdf(
      [&](Pcg32 &rng, Vec3 &w) {
        BsdfSample s;
        double a = rng.next(), b = rng.next(), c = rng.next();
        if (!bsdf.sample(a, b, c, s)) return false;
        w = s.wi;
        // The weight must be f·cos/pdf, the contract the path tracer relies on.
        Bands expectedWeight = bsdf.evaluate(s.wi) * (std::abs(s.wi.z) / bsdf.pdf(s.wi));
        for (int i = 0; i < kBandCount; ++i)
          EXPECT_NEAR(s.weight[i], expectedWeight[i], 1e-9 * (1 + expectedWeight[i]));
        return true;
      },
      [&](const Vec3 &w) { return bsdf.pdf(w); });
}

TEST(Sampling, LambertianBsdf) {
  Material m;
  m.diffuse = Bands(0.6);
  expectBsdfSamplingMatchesPdf(m, normalize(Vec3{0.3, -0.2, 0.8}));
}

TEST(Sampling, GgxLobeSmooth) {
  Material m;
  m.kind = MaterialKind::Glossy;
  m.diffuse = Bands(0.0);
  m.specular = Bands(0.9);
  m.roughness = 0.15;
  expectBsdfSamplingMatchesPdf(m, normalize(Vec3{0.5, 0.1, 0.6}));
}

TEST(Sampling, GgxLobeRoughAtGrazingAngle) {
  Material m;
  m.kind = MaterialKind::Glossy;
  m.diffuse = Bands(0.0);
  m.specular = Bands(0.8);
  m.roughness = 0.6;
  expectBsdfSamplingMatchesPdf(m, normalize(Vec3{0.9, 0.0, 0.2}));
}

TEST(Sampling, GlossyDiffusePlusGgxMixture) {
  Material m;
  m.kind = MaterialKind::Glossy;
  m.diffuse = Bands(0.4, 0.3, 0.2);
  m.specular = Bands(0.3);
  m.roughness = 0.3;
  expectBsdfSamplingMatchesPdf(m, normalize(Vec3{-0.2, 0.4, 0.7}));
}

TEST(Sampling, GgxDistributionIsNormalised) {
  // ∫ D(h) cos θh dω = 1 for any roughness (Walter et al. 2007, eq. 4); midpoint rule in θ.
  for (double alpha : {0.05, 0.3, 1.0}) {
    constexpr int kSteps = 200000;
    double integral = 0, dTheta = 0.5 * kPi / kSteps;
    for (int i = 0; i < kSteps; ++i) {
      double theta = (i + 0.5) * dTheta;
      Vec3 h{std::sin(theta), 0, std::cos(theta)};
      integral += ggxD(h, alpha) * h.z * std::sin(theta) * 2 * kPi * dTheta;
    }
    EXPECT_NEAR(integral, 1.0, 1e-6) << "alpha " << alpha;
  }
}

TEST(Sampling, UniformTriangleIsUniform) {
  // The lines b1 = i/n and b2 = j/n cut the triangle into n² congruent
  // sub-triangles of equal area: "lower" ones (i + j ≤ n − 1) and "upper" ones
  // (i + j ≤ n − 2). Each must receive 1/n² of the samples.
  constexpr int n = 16;
  auto index = [](int i, int j, bool upper) { return (i * n + j) * 2 + (upper ? 1 : 0); };
  std::vector<double> observed(2 * n * n, 0.0), expected(2 * n * n, 0.0);
  const int samples = 300000;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (i + j <= n - 1) expected[index(i, j, false)] = double(samples) / (n * n);
      if (i + j <= n - 2) expected[index(i, j, true)] = double(samples) / (n * n);
    }
  Pcg32 rng(99, 3);
  for (int k = 0; k < samples; ++k) {
    double b1, b2, u1 = rng.next(), u2 = rng.next();
    sampleUniformTriangle(u1, u2, b1, b2);
    ASSERT_GE(b1, 0);
    ASSERT_GE(b2, 0);
    ASSERT_LE(b1 + b2, 1 + 1e-12);
    int i = std::min(n - 1, static_cast<int>(b1 * n)), j = std::min(n - 1, static_cast<int>(b2 * n));
    bool upper = (b1 * n - i) + (b2 * n - j) > 1;
    observed[index(i, j, upper)] += 1;
  }
  test::ChiSquareResult r = test::chiSquare(observed, expected);
  EXPECT_EQ(r.degreesOfFreedom, n * n - 1);  // every sample landed in a real sub-triangle
  EXPECT_GT(r.pValue, test::significanceLevel(kTestsInThisFile)) << "chi² = " << r.statistic;
}

TEST(Sampling, EmittersChosenByPowerAndPointsUniformByArea) {
  Scene s;
  Material dark, bright;
  dark.emission = Bands(1.0);
  bright.emission = Bands(4.0, 2.0, 3.0);
  s.materials = {dark, bright};
  s.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 0, 0}, {7, 0, 0}, {5, 1, 0}};
  Face a, b;
  a.vertices[0] = 0;
  a.vertices[1] = 1;
  a.vertices[2] = 2;
  a.material = 0;
  b.vertices[0] = 3;
  b.vertices[1] = 4;
  b.vertices[2] = 5;
  b.material = 1;
  s.addFace(a);
  s.addFace(b);
  LightSampler lights(s);
  // Power π·A·L̄: 0.5·1 against 1·3: probabilities 1/7 and 6/7.
  ASSERT_EQ(lights.emitterCount(), 2u);
  EXPECT_NEAR(lights.selectionProbability(0), 1.0 / 7, 1e-12);
  EXPECT_NEAR(lights.pdfArea(1), (6.0 / 7) / 1.0, 1e-12);
  // Samples: which triangle, and the x coordinate's distribution on the second one
  // (uniform on a right triangle of legs 2 and 1: density of x is linear, 1 − (x−5)/2).
  constexpr int kBins = 20;
  std::vector<double> observed(kBins + 1, 0.0), expected(kBins + 1, 0.0);
  Pcg32 rng(5, 5);
  const int n = 200000;
  for (int k = 0; k < n; ++k) {
    LightSample ls;
    double u0 = rng.next(), u1 = rng.next(), u2 = rng.next();
    ASSERT_TRUE(lights.sample(u0, u1, u2, ls));
    if (ls.triangle == 0)
      observed[kBins] += 1;
    else
      observed[std::min(kBins - 1, static_cast<int>((ls.position.x - 5) / 2 * kBins))] += 1;
    EXPECT_NEAR(ls.normal.z, 1.0, 1e-12);
  }
  for (int i = 0; i < kBins; ++i) {
    double x0 = double(i) / kBins, x1 = double(i + 1) / kBins;  // in units of the leg
    // ∫ 2(1 − t) dt over [x0, x1]
    expected[i] = n * (6.0 / 7) * ((2 * x1 - x1 * x1) - (2 * x0 - x0 * x0));
  }
  expected[kBins] = n / 7.0;
  test::ChiSquareResult r = test::chiSquare(observed, expected);
  EXPECT_GT(r.pValue, test::significanceLevel(kTestsInThisFile)) << "chi² = " << r.statistic;
}

TEST(Sampling, ChiSquareTestRejectsAWrongDensity) {
  // The harness itself must be able to fail: uniform hemisphere samples against the cosine density.
  std::vector<double> observed(kThetaBins * kPhiBins + 1, 0.0);
  Pcg32 rng(1, 2);
  const int n = 100000;
  for (int k = 0; k < n; ++k) {
    double z = rng.next(), phi = 2 * kPi * rng.next(), r = std::sqrt(1 - z * z);
    observed[sphereBin({r * std::cos(phi), r * std::sin(phi), z})] += 1;
  }
  std::vector<double> expected =
      test::integratePdfOverSphereBins([](const Vec3 &w) { return cosineHemispherePdf(w.z); }, 12);
  for (double &e : expected) e *= n;
  expected.push_back(0);
  EXPECT_LT(test::chiSquare(observed, expected).pValue, 1e-6);
}

}  // namespace
}  // namespace radiant
