// The power balance of a solution, with the escaped power measured, not
// inferred: emitted = absorbed + escaped + still unshot.
//
// Every solver reports the power emitted (Σ A E plus the point lights') and
// absorbed (Σ A (1 − ρ − τ) H, from its own irradiances). What escapes — the
// light that leaves a surface and arrives at no surface's front: into the
// open through a scene's gaps, or onto the back of a one-sided face, which
// the solution holds no radiosity for — used to be written as emitted −
// absorbed, so the balance held by definition and a solver that created or
// lost light went unseen (assimp's spider: "escaped −0.26 W").
//
// Here it is measured by rays, independently of the solver's form factors:
// the power that has left the elements' fronts, Σ A (B − U) (U the
// radiosity a shooting solver has not shot yet), and the point lights'
// power, are sampled by `rays` rays (sources in proportion to their power,
// cosine-distributed about the element's normal; a light's directions
// from its own distribution), and a ray that hits nothing, a back side or a
// hidden (unmeshed) part carries its share out. Then
//
//   emitted − absorbed − escaped − unshot = Σ A B + P_lights − Σ A H − escaped
//
// (since B = E + ρH + τH' and τH' only moves power to the other side) is zero
// exactly when the irradiance the solver deposited equals what its own
// radiosities send to the surfaces: the discrepancy is the form factors'
// row-sum error (deterministic solvers), the solver's own ray noise
// (stochastic), or a bug. The estimate's standard error is
// P √(f(1 − f)/rays) for a fraction f escaping of the power P sent, about
// 0.1 % of P at the default 2^17 rays (30 ms on two cores for the Cornell box).
#pragma once

#include <cstddef>
#include <cstdint>

#include "util/spectrum.h"

namespace radiant {

class RayTracer;
struct Solution;
struct SolverOptions;

struct PowerBalance {
  Bands emitted;                    ///< Σ A E + the point lights' power, W
  Bands absorbed;                   ///< Σ A (1 − ρ − τ) H, W (the solver's)
  Bands unshot;                     ///< Σ A U: received, not yet sent on (progressive, stochastic), W
  Bands sent;                       ///< Σ A (B − U) + the point lights' power: what the rays sampled, W
  Bands escaped;                    ///< of `sent`, what reached no surface's front (measured), W
  Bands escapedToBackSides;         ///< the part of `escaped` that hit a one-sided face's back or a hidden part, W
  double escapedStandardError = 0;  ///< of escaped.average(), W
  /// emitted − absorbed − escaped − unshot, W (band average): zero for a
  /// consistent solution, to the rays' noise and the solver's own error.
  double imbalance() const { return (emitted - absorbed - escaped - unshot).average(); }
};

constexpr size_t kPowerBalanceRays = size_t(1) << 17;

/// The balance of `solution` (solved over `tracer`'s scene) with the escaped
/// power measured by `rays` rays; deterministic for a seed, whatever the threads.
PowerBalance measurePowerBalance(const RayTracer &tracer, const Solution &solution, size_t rays = kPowerBalanceRays,
                                 uint64_t seed = 1);

/// The imbalance |emitted − absorbed − escaped − unshot| a correct solver may
/// leave, W (band average), from the errors it states itself:
///
/// - noise: 4 standard errors of the escaped power's estimate, and for
///   `stochastic` of its own rays' (each iteration shoots N_k ∝ its power
///   P_k, so Σ P_k² f(1 − f)/N_k ≤ P²/(4 N_1), N_1 its first iteration's rays);
/// - convergence: a sweeping solver stops with B − E known to `residual` of
///   its largest value, so H, gathered once more, may differ by that over
///   every element: residual × max(B − E)/ρ̄ × Σ A. Shooting solvers count
///   what they have not shot as `unshot` instead;
/// - discretisation: an element's H stands for its mean, but the solver
///   gathers it at points (a centre, the nodes): by at most how far its H
///   strays from the values at its corners that the solution itself gives
///   (nodeValues, or the exact node irradiance of hierarchical-exact and
///   the stochastic solver's direct light), Σ A_e max_k |H(node_k) − H_e|.
///   This is the error estimate each element already reports (C&W ch. 6),
///   in irradiance instead of radiosity; it falls as the mesh is refined;
/// - hierarchical-exact's stated tolerances: directTolerance of the emitted
///   power (the direct light's) and linkError of all that arrives, Σ A H.
double powerBalanceTolerance(const Solution &solution, const SolverOptions &options, const PowerBalance &balance);

}  // namespace radiant
