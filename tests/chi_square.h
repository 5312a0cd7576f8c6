// Pearson's chi-square goodness-of-fit test, for sampling routines
// (Mitsuba 3's chi2 tests follow the same recipe: bin, integrate the claimed
// density over each bin, pool sparse bins, compare).
#pragma once

#include <cmath>
#include <vector>

namespace radiant::test {

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
