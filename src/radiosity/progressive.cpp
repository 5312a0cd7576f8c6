// `progressive` — progressive refinement radiosity (Cohen, Chen, Wallace &
// Greenberg, SIGGRAPH 1988) with ray-cast form factors (Wallace, Elmquist &
// Haines, SIGGRAPH 1989).
//
// Repeatedly the element with the largest unshot power ΔB·A shoots it: every
// other element j receives ΔB_j = ρ_j ΔB_i F(dA_j → A_i), the form factor from
// j's centre to the shooter's polygon, estimated with `visibilitySamples`
// stratified shadow rays. Stops when the unshot power is below `tolerance`
// of the emitted power.
//
// Two things the renderers need are kept on the way:
// * the ambient term (display only): Σ ΔB_j A_j / (Σ A − Σ ρ A), which makes
//   the picture plausible from the first shot, and exact in a furnace;
// * the direct / indirect split: what emitters shoot of their *emission*
//   lands in `direct`, everything shot after a reflection in `indirect`, so
//   Shirley's method can recompute the direct part per pixel and add only
//   the indirect one from the solution (C&W §9.3.1).
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <optional>

#include "cluster/cluster.h"
#include "radiosity/backprojection.h"
#include "radiosity/form_factor.h"
#include "radiosity/hemicube.h"
#include "radiosity/solver.h"
#include "radiosity/transmission.h"
#include "util/error.h"

namespace radiant {

namespace {

/// Σ ΔB_j A_j / (Σ A − Σ ρ A), per band (rad.c's GetAmbient), and its
/// indirect part. Unshot power U spreads as (U/A)(1 + ρ̄ + ρ̄² + …); for the
/// still-unshot emission U_E the first term is direct light, which per-pixel
/// emitter sampling already counts, so the indirect part is
/// (U_R + ρ̄ U_E) / (Σ A − Σ ρ A), with U_R the unshot reflected power.
void ambientTerms(Solution &s, const std::vector<Bands> &unshotEmission) {
  Bands unshotPower(0.0), unshotEmitted(0.0), area(0.0), reflectedArea(0.0);
  for (size_t j = 0; j < s.elementCount(); ++j) {
    double a = s.mesh.elements[j].area;
    unshotPower += s.unshot[j] * a;
    unshotEmitted += unshotEmission[j] * a;
    area += Bands(a);
    reflectedArea += (s.reflectance[j] + s.transmittanceOf(j)) * a;  // scattered to either side
  }
  s.ambient = s.indirectAmbient = Bands(0.0);
  for (int b = 0; b < kBandCount; ++b) {
    const double absorbing = area[b] - reflectedArea[b];
    if (!(absorbing > 0)) continue;
    const double meanReflectance = reflectedArea[b] / area[b];
    s.ambient[b] = unshotPower[b] / absorbing;
    s.indirectAmbient[b] = (unshotPower[b] - unshotEmitted[b] * (1 - meanReflectance)) / absorbing;
  }
}

}  // namespace

void solveProgressive(const RayTracer &tracer, Solution &s, const SolverOptions &options,
                      const SolverProgressCallback &progress) {
  const size_t n = s.elementCount();
  const auto start = std::chrono::steady_clock::now();
  std::vector<Bands> unshotEmission = s.emission;  // not yet shot emission: becomes `direct` where it lands
  std::vector<Bands> unshotReflected(n, Bands(0.0));
  // Light through translucent faces (transmission.h): what arrives on one
  // side gains τH on the other, shot on like reflected light.
  const ElementTransmission transmission(tracer.scene(), s);
  auto gainAt = [&](size_t j, const Bands &directGain, const Bands &indirectGain) {
    s.direct[j] += directGain;
    s.indirect[j] += indirectGain;
    s.radiosity[j] += directGain + indirectGain;
    unshotReflected[j] += directGain + indirectGain;
    s.unshot[j] += directGain + indirectGain;
  };
  // Point lights shoot first, exactly (backprojection.h): ρH is direct light
  // received, to be shot on as reflected light.
  if (const std::vector<Bands> h = pointLightIrradianceOfElements(tracer, s); !h.empty())
    for (size_t j = 0; j < n; ++j) {
      s.irradiance[j] += h[j];
      gainAt(j, s.reflectance[j] * h[j], Bands(0.0));
      transmission.pass(j, h[j], [&](uint32_t to, const Bands &gain) { gainAt(to, gain, Bands(0.0)); });
    }
  std::vector<Bands> &irradiance = s.irradiance;  // H: what arrived, for reports and the energy balance
  std::vector<std::vector<Vec3>> polygons(n);
  for (uint32_t j = 0; j < n; ++j) polygons[j] = s.mesh.polygon(j);
  const double emitted = s.stats.emittedPower.average();

  auto unshotPowerFraction = [&]() {
    double unshot = 0;
    for (size_t j = 0; j < n; ++j) unshot += s.unshot[j].average() * s.mesh.elements[j].area;
    return emitted > 0 ? unshot / emitted : 0.0;
  };

  enum class Estimator { Analytic, RayCast, Hemicube };
  Estimator estimator = Estimator::Analytic;
  if (options.formFactor == "ray-cast")
    estimator = Estimator::RayCast;
  else if (options.formFactor == "hemicube")
    estimator = Estimator::Hemicube;
  else if (options.formFactor != "analytic")
    throw InputError(InputLocation::ofParameter("form-factor"), "unknown form-factor estimator '" + options.formFactor +
                                                                    "' (expected analytic, ray-cast or hemicube)");
  std::optional<Hemicube> hemicube;
  if (estimator == Estimator::Hemicube) hemicube.emplace(options.hemicubeResolution);
  // A hemicube pixel counts for the element it sees, if it sees that element's front.
  Vec3 hemicubeCentre;
  std::function<int(const Hit &)> frontElementOf = [&](const Hit &hit) -> int {
    if (s.mesh.patchOfFace[hit.face] < 0 || dot(hit.geometricNormal, hit.position - hemicubeCentre) >= 0) return -1;
    return static_cast<int>(s.mesh.locate(hit.face, hit.position).element);
  };

  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  const int maxShots = options.maxIterations > 0 ? options.maxIterations : 1'000'000;
  s.stats.residual = unshotPowerFraction();
  int shot = 0;
  while (shot < maxShots && s.stats.residual >= options.tolerance) {
    // The shooter: the largest unshot power (averaged over bands).
    size_t shooter = 0;
    double largest = -1;
    for (size_t j = 0; j < n; ++j) {
      double power = s.unshot[j].average() * s.mesh.elements[j].area;
      if (power > largest) {
        largest = power;
        shooter = j;
      }
    }
    if (largest <= 0) break;
    const Bands shootEmission = unshotEmission[shooter], shootReflected = unshotReflected[shooter];
    const Vec3 shooterNormal = s.mesh.normalOf(static_cast<uint32_t>(shooter));
    const uint32_t shooterPatch = s.mesh.elements[shooter].patch;
    unshotEmission[shooter] = unshotReflected[shooter] = s.unshot[shooter] = Bands(0.0);
    std::vector<double> formFactor(n, 0.0);
    std::atomic<size_t> receiversTraced{0};

    if (estimator == Estimator::Hemicube) {
      // One hemicube at the shooter's centre gives F_ij for every j it sees;
      // reciprocity turns it into F_ji, clamped to 1 (rad.c) for tiny receivers.
      Pcg32 rng = sampleGenerator(options.seed, shooter, uint64_t(shot) + 1);
      const Element &source = s.mesh.elements[shooter];
      hemicubeCentre = source.centre;
      hemicube->gather(tracer, source.centre, shooterNormal, frontElementOf, formFactor, rng);
      for (size_t j = 0; j < n; ++j)
        formFactor[j] = s.mesh.elements[j].patch == shooterPatch
                            ? 0.0
                            : std::min(1.0, formFactor[j] * source.area / s.mesh.elements[j].area);
    } else {
      // With MPI ranks, rank r takes the receivers j = r mod N, each from its
      // own generator, and the form factors are summed over the ranks: every
      // rank shoots alike, and the solution is one process's bit for bit.
      const size_t ranks = size_t(cluster::size()), me = size_t(cluster::rank());
      arena.execute([&] {
        tbb::parallel_for(size_t(0), n, [&](size_t j) {
          if (j % ranks != me) return;
          const Element &receiver = s.mesh.elements[j];
          if (receiver.patch == shooterPatch) return;
          const Vec3 &receiverNormal = s.mesh.normalOf(static_cast<uint32_t>(j));
          // Only the shooter's front emits: a receiver behind its plane gets nothing.
          if (dot(receiver.centre - polygons[shooter][0], shooterNormal) <= 0) return;
          Pcg32 rng = sampleGenerator(options.seed, j, uint64_t(shot) + 1);
          if (estimator == Estimator::RayCast) {
            formFactor[j] = formFactorRayCast(tracer, receiver.centre, receiverNormal, polygons[shooter], shooterNormal,
                                              options.visibilitySamples, rng);
            ++receiversTraced;
          } else {
            double f = formFactorPointToPolygon(receiver.centre, receiverNormal, polygons[shooter]);
            if (f > 0) {
              f *= visibleFraction(tracer, receiver.centre, receiverNormal, polygons[shooter], shooterNormal,
                                   options.visibilitySamples, rng);
              ++receiversTraced;
            }
            formFactor[j] = f;
          }
        });
      });
      if (cluster::distributed()) {
        cluster::sumOnAllRanks(formFactor.data(), n);
        int64_t traced = int64_t(receiversTraced.load());
        cluster::sumOnAllRanks(&traced, 1);
        receiversTraced = size_t(traced);
      }
    }
    for (size_t j = 0; j < n; ++j) {
      if (formFactor[j] <= 0) continue;
      Bands fromEmission = shootEmission * formFactor[j], fromReflection = shootReflected * formFactor[j];
      irradiance[j] += fromEmission + fromReflection;
      gainAt(j, s.reflectance[j] * fromEmission, s.reflectance[j] * fromReflection);
      transmission.pass(j, fromEmission, [&](uint32_t to, const Bands &gain) { gainAt(to, gain, Bands(0.0)); });
      transmission.pass(j, fromReflection, [&](uint32_t to, const Bands &gain) { gainAt(to, Bands(0.0), gain); });
    }
    // Shadow rays cast (at most: samples behind a receiver's plane are skipped).
    const size_t k = size_t(std::max(1L, std::lround(std::sqrt(double(options.visibilitySamples)))));
    s.stats.formFactorRays += estimator == Estimator::Hemicube
                                  ? size_t(3) * hemicube->resolution() * hemicube->resolution()
                              : estimator == Estimator::RayCast ? receiversTraced * size_t(options.visibilitySamples)
                                                                : receiversTraced * k * k;
    ++shot;
    s.stats.iterations = shot;
    s.stats.residual = unshotPowerFraction();
    if (progress)
      progress({shot, s.stats.residual, options.tolerance,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
  }

  ambientTerms(s, unshotEmission);
  // The escaped and unshot power are measured by solveRadiosity (power_balance.h), not inferred from this.
  s.stats.absorbedPower = Bands(0.0);
  for (size_t j = 0; j < n; ++j) s.stats.absorbedPower += s.absorptance(j) * irradiance[j] * s.mesh.elements[j].area;
}

}  // namespace radiant
