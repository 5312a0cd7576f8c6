// atan2(y, x) for y ≥ 0 — the angle between two vectors from |a × b| and
// a·b — to double precision, at a fraction of libm's cost: Lambert's contour
// integral (radiosity/form_factor.h) takes one per polygon edge, and the
// default solver evaluates it some ten million times on the Cornell box.
//
// The approximation is Moshier's (Cephes, atan.c): the argument reduced to
// [0, 0.66] by atan(t) = π/4 + atan((t − 1)/(t + 1)) or π/2 − atan(1/t), then
// t + t³·P(t²)/Q(t²) with a degree-4/5 rational function; error under
// 2·10⁻¹⁶ relative (tested against std::atan2).
#pragma once

namespace radiant {

/// atan(t) for t ≥ 0.
inline double atanNonNegative(double t) {
  constexpr double kPiOver2 = 1.57079632679489661923, kPiOver4 = 0.78539816339744830962;
  constexpr double kTan3PiOver8 = 2.41421356237309504880, kMoreBits = 6.123233995736765886130e-17;
  double base = 0, extra = 0;
  if (t > kTan3PiOver8) {
    base = kPiOver2, extra = kMoreBits;
    t = -1 / t;
  } else if (t > 0.66) {
    base = kPiOver4, extra = 0.5 * kMoreBits;
    t = (t - 1) / (t + 1);
  }
  const double z = t * t;
  const double p =
      (((-8.750608600031904122785e-1 * z - 1.615753718733365076637e1) * z - 7.500855792314704667340e1) * z -
       1.228866684490136173410e2) *
          z -
      6.485021904942025371773e1;
  const double q =
      ((((z + 2.485846490142306297962e1) * z + 1.650270098316988542046e2) * z + 4.328810604912902668951e2) * z +
       4.853903996359136964868e2) *
          z +
      1.945506571482613964425e2;
  return base + (t * (z * p / q) + t + extra);
}

/// atan2(y, x) for y ≥ 0 (in [0, π]); 0 when both are 0.
inline double angleFromSineAndCosine(double y, double x) {
  constexpr double kPi = 3.14159265358979323846, kPiOver2 = 1.57079632679489661923;
  if (x > 0) return atanNonNegative(y / x);
  if (x < 0) return kPi - atanNonNegative(y / -x);
  return y > 0 ? kPiOver2 : 0.0;
}

}  // namespace radiant
