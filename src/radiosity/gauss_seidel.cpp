// `gauss-seidel` — gathering on the element matrix (Cohen & Wallace §5.3).
//
// B_i = E_i + ρ_i Σ_j F_ij B_j (+ τ_i H' through a translucent face,
// radiosity/transmission.h), swept in place until the largest change of B
// in a sweep, relative to the largest reflected radiosity B − E, falls below
// the tolerance. F_ij is the
// form factor from element i's centre to the front of element j's polygon: exact
// (Lambert's contour integral, clipped to i's tangent plane) times the
// fraction of `visibilitySamples` stratified points on j that i's centre sees.
//
// The whole matrix is stored, so this is the solver for small meshes (up to
// a few thousand elements) and for checking the others against; its cost and
// memory grow as n². With MPI ranks, rank r computes the rows i = r mod N
// (each from its own generator) and the ranks share them, so every rank
// sweeps the same matrix: one process's solution, bit for bit.
#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <cstring>

#include "cluster/cluster.h"
#include "radiosity/backprojection.h"
#include "radiosity/form_factor.h"
#include "radiosity/solver.h"
#include "radiosity/transmission.h"
#include "util/error.h"

namespace radiant {

namespace {
constexpr size_t kMaxGaussSeidelElements = 8000;  // 8000² form factors of 8 bytes at worst: 0.5 GB

struct Coupling {
  uint32_t element;
  float formFactor;
};

/// Every rank's rows on every rank: first their lengths, then their
/// couplings as bytes at the offsets the lengths give (a byte-wise sum of
/// one rank's bytes and zeros is those bytes).
template <typename Owns>
void shareRows(std::vector<std::vector<Coupling>> &rows, std::vector<size_t> &visibilityRays, const Owns &owns) {
  const size_t n = rows.size();
  std::vector<int64_t> counts(2 * n, 0);  // per row: its length, its rays
  for (size_t i = 0; i < n; ++i)
    if (owns(i)) counts[2 * i] = int64_t(rows[i].size()), counts[2 * i + 1] = int64_t(visibilityRays[i]);
  cluster::sumOnAllRanks(counts.data(), counts.size());
  std::vector<size_t> offset(n + 1, 0);
  for (size_t i = 0; i < n; ++i) offset[i + 1] = offset[i] + size_t(counts[2 * i]);
  std::vector<uint8_t> bytes(offset[n] * sizeof(Coupling), 0);
  for (size_t i = 0; i < n; ++i)
    if (owns(i) && !rows[i].empty())
      std::memcpy(&bytes[offset[i] * sizeof(Coupling)], rows[i].data(), rows[i].size() * sizeof(Coupling));
  cluster::sumOnAllRanks(bytes.data(), bytes.size());
  for (size_t i = 0; i < n; ++i) {
    visibilityRays[i] = size_t(counts[2 * i + 1]);
    if (owns(i)) continue;
    rows[i].resize(size_t(counts[2 * i]));
    if (!rows[i].empty())
      std::memcpy(rows[i].data(), &bytes[offset[i] * sizeof(Coupling)], rows[i].size() * sizeof(Coupling));
  }
}
}  // namespace

void solveGaussSeidel(const RayTracer &tracer, Solution &s, const SolverOptions &options,
                      const SolverProgressCallback &progress) {
  const size_t n = s.elementCount();
  if (n > kMaxGaussSeidelElements)
    throw InputError(InputLocation::ofParameter("solver"),
                     fmt::format("gauss-seidel stores the full form-factor matrix and allows at most {} elements; "
                                 "this mesh has {} (use the progressive solver, or a larger mesh-size)",
                                 kMaxGaussSeidelElements, n));
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::vector<Coupling>> rows(n);
  std::vector<std::vector<Vec3>> polygons(n);
  for (uint32_t j = 0; j < n; ++j) polygons[j] = s.mesh.polygon(j);

  std::vector<size_t> visibilityRays(n, 0);
  const size_t k = size_t(std::max(1L, std::lround(std::sqrt(double(options.visibilitySamples)))));
  const size_t raysPerFactor = k * k;  // visibleFraction's stratified k × k grid
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  auto ownsRow = [](size_t i) {
    return cluster::size() == 1 || i % size_t(cluster::size()) == size_t(cluster::rank());
  };
  arena.execute([&] {
    tbb::parallel_for(size_t(0), n, [&](size_t i) {
      if (!ownsRow(i)) return;
      const Element &ei = s.mesh.elements[i];
      const Vec3 &ni = s.mesh.normalOf(static_cast<uint32_t>(i));
      Pcg32 rng = sampleGenerator(options.seed, i, 0x6a55);  // one generator per row: thread-count independent
      for (uint32_t j = 0; j < n; ++j) {
        if (s.mesh.elements[j].patch == ei.patch) continue;  // a planar patch does not see itself
        // B_j leaves j's front only: a receiver behind j's plane gets nothing from it
        // (the ceiling above the Cornell light must not see the light's emission).
        if (dot(ei.centre - polygons[j][0], s.mesh.normalOf(j)) <= 0) continue;
        double f = formFactorPointToPolygon(ei.centre, ni, polygons[j]);
        if (f <= 0) continue;
        visibilityRays[i] += raysPerFactor;
        f *= visibleFraction(tracer, ei.centre, ni, polygons[j], s.mesh.normalOf(j), options.visibilitySamples, rng);
        if (f > 0) rows[i].push_back({j, static_cast<float>(f)});
      }
    });
  });
  if (cluster::distributed()) shareRows(rows, visibilityRays, ownsRow);
  for (size_t rays : visibilityRays) s.stats.formFactorRays += rays;

  // The direct part is one gather from the emitters, ρ_i Σ_j F_ij E_j, plus
  // what the point lights give, ρ_i H_i: a source term beside the emission.
  // Through a translucent face, τ of the other side's the same.
  const std::vector<Bands> lightIrradiance = pointLightIrradianceOfElements(tracer, s);
  const ElementTransmission transmission(tracer.scene(), s);
  std::vector<Bands> source = s.emission;
  for (size_t i = 0; i < n; ++i) {
    Bands gathered(0.0);
    for (const Coupling &c : rows[i]) gathered += s.emission[c.element] * double(c.formFactor);
    if (!lightIrradiance.empty()) gathered += lightIrradiance[i];
    s.direct[i] += s.reflectance[i] * gathered;
    transmission.pass(i, gathered, [&](uint32_t to, const Bands &gain) { s.direct[to] += gain; });
    if (!lightIrradiance.empty()) {
      source[i] += s.reflectance[i] * lightIrradiance[i];
      transmission.pass(i, lightIrradiance[i], [&](uint32_t to, const Bands &gain) { source[to] += gain; });
    }
  }
  // H of every element as last gathered (without the point lights, which
  // `source` holds), for what passes through to the other side.
  const std::vector<std::vector<std::pair<uint32_t, double>>> incoming = transmission.incoming();
  std::vector<Bands> lastGathered(transmission.empty() ? 0 : n, Bands(0.0));

  const int maxSweeps = options.maxIterations > 0 ? options.maxIterations : 10000;
  for (int sweep = 1; sweep <= maxSweeps; ++sweep) {
    double largestChange = 0, largest = 0;
    for (size_t i = 0; i < n; ++i) {
      Bands gathered(0.0);
      for (const Coupling &c : rows[i]) gathered += s.radiosity[c.element] * double(c.formFactor);
      Bands updated = source[i] + s.reflectance[i] * gathered;
      if (!lastGathered.empty()) {
        lastGathered[i] = gathered;
        for (const auto &[from, weight] : incoming[i]) updated += s.transmittanceOf(i) * lastGathered[from] * weight;
      }
      for (int b = 0; b < kBandCount; ++b) {
        largestChange = std::max(largestChange, std::abs(updated[b] - s.radiosity[i][b]));
        // Against the largest *reflected* radiosity: next to an emitter's B the
        // walls' changes would look negligible long before they are.
        largest = std::max(largest, std::abs(updated[b] - s.emission[i][b]));
      }
      s.radiosity[i] = updated;
    }
    s.stats.iterations = sweep;
    s.stats.residual = largest > 0 ? largestChange / largest : 0;
    if (progress)
      progress({sweep, s.stats.residual, options.tolerance,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
    if (s.stats.residual < options.tolerance) break;
  }

  // Energy balance: irradiance H_i = Σ F_ij B_j; absorbed Σ A (1−ρ) H.
  s.stats.absorbedPower = Bands(0.0);
  for (size_t i = 0; i < n; ++i) {
    Bands irradiance(0.0);
    for (const Coupling &c : rows[i]) irradiance += s.radiosity[c.element] * double(c.formFactor);
    if (!lightIrradiance.empty()) irradiance += lightIrradiance[i];
    s.irradiance[i] = irradiance;
    s.stats.absorbedPower += s.absorptance(i) * irradiance * s.mesh.elements[i].area;
    s.indirect[i] = s.radiosity[i] - s.emission[i] - s.direct[i];
    s.unshot[i] = Bands(0.0);
  }
  // The escaped power is measured by solveRadiosity (power_balance.h), not inferred from these.
  s.ambient = Bands(0.0);
}

}  // namespace radiant
