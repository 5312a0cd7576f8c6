// Pearson's chi-square goodness-of-fit test, for sampling routines
// (Mitsuba 3's chi2 tests follow the same recipe: bin, integrate the claimed
// density over each bin, pool sparse bins, compare).
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "util/math.h"

namespace radiant::test {

/// Bins of equal solid angle over the whole sphere: 24 in cos θ ∈ [−1, 1] by 48 in φ ∈ [0, 2π).
constexpr int kThetaBins = 24, kPhiBins = 48;
inline int sphereBin(const Vec3 &w) {
  int i = std::clamp(static_cast<int>((w.z + 1) / 2 * kThetaBins), 0, kThetaBins - 1);
  double phi = std::atan2(w.y, w.x);
  if (phi < 0) phi += 2 * kPi;
  int j = std::clamp(static_cast<int>(phi / (2 * kPi) * kPhiBins), 0, kPhiBins - 1);
  return i * kPhiBins + j;
}

/// ∫ pdf dω over each sphereBin, by the midpoint rule on a sub × sub grid per bin.
inline std::vector<double> integratePdfOverSphereBins(const std::function<double(const Vec3 &)> &pdf, int sub) {
  std::vector<double> integral(kThetaBins * kPhiBins, 0.0);
  const double dz = 2.0 / (kThetaBins * sub), dphi = 2 * kPi / (kPhiBins * sub);
  for (int a = 0; a < kThetaBins * sub; ++a) {
    double z = -1 + (a + 0.5) * dz, r = std::sqrt(std::max(0.0, 1 - z * z));
    for (int b = 0; b < kPhiBins * sub; ++b) {
      double phi = (b + 0.5) * dphi;
      Vec3 w{r * std::cos(phi), r * std::sin(phi), z};
      integral[(a / sub) * kPhiBins + b / sub] += pdf(w) * dz * dphi;
    }
  }
  return integral;
}

/// Regularised upper incomplete gamma Q(a, x) (Numerical Recipes §6.2).
inline double gammaQ(double a, double x) {
  if (x <= 0) return 1;
  double lnGammaA = std::lgamma(a);
  if (x < a + 1) {  // series for P, then Q = 1 − P
    double sum = 1 / a, term = sum;
    for (int n = 1; n < 100000; ++n) {
      term *= x / (a + n);
      sum += term;
      if (std::abs(term) < std::abs(sum) * 1e-15) break;
    }
    return 1 - sum * std::exp(-x + a * std::log(x) - lnGammaA);
  }
  // Continued fraction (modified Lentz).
  double b = x + 1 - a, c = 1e300, d = 1 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < 1e-300) d = 1e-300;
    c = b + an / c;
    if (std::abs(c) < 1e-300) c = 1e-300;
    d = 1 / d;
    double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1) < 1e-15) break;
  }
  return std::exp(-x + a * std::log(x) - lnGammaA) * h;
}

struct ChiSquareResult {
  double statistic = 0;
  int degreesOfFreedom = 0;
  double pValue = 1;
};

/// Observed counts against expected counts; bins expected below `minExpected`
/// are pooled into one (the chi-square approximation needs ≳ 5 per bin).
inline ChiSquareResult chiSquare(const std::vector<double> &observed, const std::vector<double> &expected,
                                 double minExpected = 5) {
  ChiSquareResult r;
  double pooledObserved = 0, pooledExpected = 0;
  int bins = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] < minExpected) {
      pooledObserved += observed[i];
      pooledExpected += expected[i];
      continue;
    }
    r.statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    ++bins;
  }
  if (pooledExpected > 0) {
    r.statistic += (pooledObserved - pooledExpected) * (pooledObserved - pooledExpected) / pooledExpected;
    ++bins;
  } else if (pooledObserved > 0) {
    r.statistic = INFINITY;  // samples where the density claims none
  }
  r.degreesOfFreedom = bins - 1;
  r.pValue = r.degreesOfFreedom > 0 ? gammaQ(0.5 * r.degreesOfFreedom, 0.5 * r.statistic) : 1;
  return r;
}

/// Significance for one test of `testCount` run together (Šidák correction of 1%).
inline double significanceLevel(int testCount) {
  return 1 - std::pow(1 - 0.01, 1.0 / testCount);
}

}  // namespace radiant::test
