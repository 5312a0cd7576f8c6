#include "radiosity/receiver_polynomial.h"

#include <stdexcept>

namespace radiant {

namespace {

/// P = (Σ w φ φᵀ)⁻¹ [w_k φ_k]: the fit's coefficients are P times the values.
struct FitMatrix {
  int terms = 0, points = 0;
  double p[4][9] = {};
};

FitMatrix makeFit(bool quad) {
  const std::vector<CubaturePoint> &rule = receiverRule(quad);
  FitMatrix f;
  f.terms = quad ? 4 : 3;
  f.points = static_cast<int>(rule.size());
  auto basis = [&](const CubaturePoint &q, int t) { return t == 0 ? 1.0 : t == 1 ? q.u : t == 2 ? q.v : q.u * q.v; };
  // Normal matrix, inverted by Gauss–Jordan elimination (it is small and well conditioned).
  double a[4][8] = {};
  for (int i = 0; i < f.terms; ++i) {
    for (int j = 0; j < f.terms; ++j)
      for (const CubaturePoint &q : rule) a[i][j] += q.weight * basis(q, i) * basis(q, j);
    a[i][f.terms + i] = 1;
  }
  for (int col = 0; col < f.terms; ++col) {
    int pivot = col;
    for (int r = col + 1; r < f.terms; ++r)
      if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
    for (int k = 0; k < 2 * f.terms; ++k) std::swap(a[col][k], a[pivot][k]);
    const double d = a[col][col];
    if (!(std::abs(d) > 1e-12)) throw std::logic_error("receiver polynomial: singular fit");
    for (int k = 0; k < 2 * f.terms; ++k) a[col][k] /= d;
    for (int r = 0; r < f.terms; ++r) {
      if (r == col) continue;
      const double m = a[r][col];
      for (int k = 0; k < 2 * f.terms; ++k) a[r][k] -= m * a[col][k];
    }
  }
  for (int i = 0; i < f.terms; ++i)
    for (int k = 0; k < f.points; ++k) {
      double s = 0;
      for (int j = 0; j < f.terms; ++j) s += a[i][f.terms + j] * rule[k].weight * basis(rule[k], j);
      f.p[i][k] = s;
    }
  return f;
}

}  // namespace

const std::vector<CubaturePoint> &receiverRule(bool quad) {
  static const std::vector<CubaturePoint> quadRule = [] {
    const double g[3] = {0.5 - 0.5 * std::sqrt(0.6), 0.5, 0.5 + 0.5 * std::sqrt(0.6)};
    const double w[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};
    std::vector<CubaturePoint> r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r.push_back({g[i], g[j], w[i] * w[j]});
    return r;
  }();
  static const std::vector<CubaturePoint> triangleRule = [] {
    const double a = 0.445948490915965, b = 0.108103018168070, wa = 0.223381589678011;
    const double c = 0.091576213509771, d = 0.816847572980459, wc = 0.109951743655322;
    return std::vector<CubaturePoint>{{a, a, wa}, {b, a, wa}, {a, b, wa}, {c, c, wc}, {d, c, wc}, {c, d, wc}};
  }();
  return quad ? quadRule : triangleRule;
}

ReceiverPolynomial<double> fitReceiverPolynomial(bool quad, std::span<const double> values) {
  static const FitMatrix quadFit = makeFit(true), triangleFit = makeFit(false);
  const FitMatrix &f = quad ? quadFit : triangleFit;
  ReceiverPolynomial<double> p;
  for (int i = 0; i < f.terms; ++i) {
    double s = 0;
    for (int k = 0; k < f.points; ++k) s += f.p[i][k] * values[k];
    p.c[i] = s;
  }
  return p;
}

}  // namespace radiant
