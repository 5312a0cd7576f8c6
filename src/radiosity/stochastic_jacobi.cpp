// `stochastic` — stochastic Jacobi radiosity with incremental shooting
// (Neumann et al. 1994; Bekaert, "Hierarchical and stochastic algorithms for
// radiosity", 1999, ch. 4), the solver for scenes too large to link every
// pair of patches.
//
// Each iteration shoots all the unshot power at once with rays: N rays, N in
// proportion to the unshot power left, each from an element chosen with
// probability ∝ its unshot power, from a uniform point on it, in a
// cosine-distributed direction about its front normal. A ray carries the
// total unshot power / N (coloured by its source's unshot radiosity); the
// element it hits (front side) receives it as irradiance and keeps ρ of it as
// new unshot radiosity. The form factors are never computed: the rays sample
// them, and the cost per iteration is O(N log n) in rays through Embree, not
// O(n²). Iterations stop when the unshot power falls below the tolerance.
//
// The estimate is noisy: an element hit by k rays has a relative error of
// about 1/√k. `raysPerElement` sets the first iteration's N as a multiple of
// the element count. Deterministic: rays are drawn in fixed chunks with
// their own generators, whatever the thread count.
//
// The direct light is not left to the rays by default (directLightAtNodes): it is
// computed exactly at the mesh's nodes and averaged over each element
// (node_direct_light.h), so shadows and the shading of a tessellated model
// carry no noise; the rays then shoot the reflected light only, and the
// display reads it at the nodes through a density estimate wherever an
// element is too small to hold enough rays of its own
// (reflected_light_density.h). With direct=rays the first iteration shoots
// the emission as the rest, and `direct` is kept apart from `indirect` as in
// the progressive solver.
//
// Several MPI ranks (cluster/cluster.h) split each iteration's chunks, rank
// r taking every chunk c with c mod N = r, and sum the power that arrived
// at each element. That sum is kept in fixed point (kArrivalScale units of
// the iteration's unshot power): integer addition does not depend on the
// order, so the solution is bit for bit the same for any number of ranks
// and threads. The rest of an iteration (O(n)) runs on every rank alike.
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "cluster/cluster.h"
#include "radiosity/backprojection.h"
#include "radiosity/node_direct_light.h"
#include "radiosity/reflected_light_density.h"
#include "radiosity/reflected_light_gather.h"
#include "radiosity/solve_checkpoint.h"
#include "radiosity/solver.h"
#include "radiosity/transmission.h"
#include "util/interrupt.h"
#include "util/sampling.h"

namespace radiant {

namespace {

struct Deposit {
  uint32_t element;
  Bands power;  ///< W per band arriving at the element's front
};

/// Fixed-point units per watt of an iteration's unshot power: 2^60. A band
/// of one ray carries at most kBandCount × its share, so all the iteration's
/// rays together stay below 2^62 units (int64); one unit is 2^−60 of the
/// shot power, far below one ray's share of it.
constexpr double kArrivalScale = 0x1.0p60 / kBandCount;

/// Rays a node's elements must hold for their own mean to be its reflected
/// light (reflected_light_density.h): 400 rays, a relative error of about 5 %.
constexpr double kEnoughRays = 400;

/// The final gather's rays at a node whose elements hold enough rays of
/// their own (a wall's, a few thousand nodes): their mean is accurate but
/// flat across each element, where a room's corner or the floor beside a
/// model darkens; 256 stratified rays read that with about the elements'
/// own noise (cornell-knots: RMSE 0.00211 → 0.00198, 0.4 s).
constexpr int kGatherRaysWhereEnough = 256;

/// The final gather's rays at the nodes whose elements hold fewer
/// (reflected_light_gather.h): 32 a node, fewer (down to 16) where the
/// nodes are many, so that it costs at most about this many rays. On
/// cornell-knots 64, 32 and 16 rays gave the same image RMSE (0.00235,
/// 0.00236, 0.00239: the pooling over neighbours takes the noise), for
/// whole runs of 9.2, 7.8 and 7.3 s.
constexpr size_t kGatherRays = 16'000'000;

}  // namespace

void solveStochasticJacobi(const RayTracer &tracer, Solution &s, const SolverOptions &options,
                           const SolverProgressCallback &progress) {
  const size_t n = s.elementCount();
  const auto start = std::chrono::steady_clock::now();
  const double emitted = s.stats.emittedPower.average();
  if (n == 0 || emitted <= 0) return;
  const size_t firstRays = std::max<size_t>(1000, n * size_t(std::max(1, options.raysPerElement)));
  constexpr size_t kChunk = 4096;

  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  const bool timing = std::getenv("RADIANT_TIMING") != nullptr;
  // Where a ray lands: a face meshed as one element is that element, found
  // without reading its patch (4 bytes a face instead of a patch record and
  // its corners: most of a 10⁶-triangle model's faces).
  const std::vector<int32_t> wholeFaceElement = s.mesh.wholeFaceElements();
  std::vector<double> raysArrived(n, 0.0);  // per element, over the iterations
  const int maxIterations = options.maxIterations > 0 ? options.maxIterations : 1000;

  const ElementTransmission transmission(tracer.scene(), s);
  // With the direct light at the nodes (node_direct_light.h), each element
  // starts from ρ·H_direct, its exact irradiance's mean over it, as if the
  // emission had been shot; the rays carry the reflected light only.
  std::vector<Bands> lightGain, elementDirect;
  bool emissionFirst = false;
  const bool directAtNodes = directLightAtNodes(options, tracer.scene());
  if (directAtNodes) {
    MeshDirectLight light = directLightOfMesh(tracer, s, options.threads);
    s.nodeDirectIrradiance = std::move(light.atNodes);
    elementDirect = std::move(light.ofElements);
    if (timing)
      std::fprintf(stderr, "  %-28s %.3f s\n", "direct light at the nodes",
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (!transmission.empty()) s.transmittedDirect.assign(n, Bands(0.0)), s.transmittedIndirect.assign(n, Bands(0.0));
    for (size_t e = 0; e < n; ++e) s.unshot[e] = Bands(0.0);  // the emission has arrived
    for (size_t e = 0; e < n; ++e) {
      const Bands &h = elementDirect[e];
      const Bands gain = s.reflectance[e] * h;
      s.irradiance[e] += h;
      s.radiosity[e] += gain, s.direct[e] += gain, s.unshot[e] += gain;
      transmission.pass(e, h, [&](uint32_t to, const Bands &through) {
        s.radiosity[to] += through, s.direct[to] += through, s.unshot[to] += through;
        s.transmittedDirect[to] += through;
      });
    }
  } else {
    // Point lights shoot first, exactly (backprojection.h): ρH is direct light
    // already received, and is shot on as reflected light once the emission
    // has been (iteration 1 stays the emitters' direct light).
    // Through a translucent face (transmission.h) the other side gains τH of
    // what arrives, shot on with the reflected light.
    if (const std::vector<Bands> h = pointLightIrradianceOfElements(tracer, s); !h.empty()) {
      lightGain.assign(n, Bands(0.0));
      for (size_t e = 0; e < n; ++e) {
        lightGain[e] += s.reflectance[e] * h[e];
        transmission.pass(e, h[e], [&](uint32_t to, const Bands &gain) { lightGain[to] += gain; });
        s.irradiance[e] += h[e];
      }
      for (size_t e = 0; e < n; ++e) s.radiosity[e] += lightGain[e], s.direct[e] += lightGain[e];
    }
    for (size_t e = 0; e < n && !emissionFirst; ++e) emissionFirst = s.unshot[e].max() > 0;
  }
  auto shootLightGain = [&] {
    for (size_t e = 0; e < lightGain.size(); ++e) s.unshot[e] += lightGain[e];
    lightGain.clear();
  };
  if (!emissionFirst) shootLightGain();

  // A checkpoint (solve_checkpoint.h): the state after its iteration replaces
  // all of the above, and the solve goes on from the next.
  const SolveCheckpointOptions &checkpoint = options.checkpoint;
  int firstIteration = 1;
  if (!checkpoint.path.empty() && checkpoint.resume && std::filesystem::exists(checkpoint.path)) {
    StochasticCheckpoint saved = readStochasticCheckpoint(checkpoint.path, checkpoint.job, n);
    s.radiosity = std::move(saved.radiosity), s.direct = std::move(saved.direct);
    s.indirect = std::move(saved.indirect), s.unshot = std::move(saved.unshot);
    s.irradiance = std::move(saved.irradiance), lightGain = std::move(saved.lightGain);
    s.transmittedDirect = std::move(saved.transmittedDirect);
    s.transmittedIndirect = std::move(saved.transmittedIndirect);
    raysArrived = std::move(saved.raysArrived);
    emissionFirst = saved.emissionFirst;
    s.stats.formFactorRays = saved.formFactorRays;
    s.stats.iterations = saved.iteration;
    s.stats.resumedFromIteration = saved.iteration;
    firstIteration = saved.iteration + 1;
  }
  auto lastCheckpoint = std::chrono::steady_clock::now();
  // Rank 0 writes (every rank holds the same state: cluster/cluster.h).
  auto saveCheckpoint = [&](int iteration) {
    if (!cluster::isRoot()) return;
    StochasticCheckpoint state;
    state.iteration = iteration;
    state.emissionFirst = emissionFirst;
    state.formFactorRays = s.stats.formFactorRays;
    state.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.radiosity = s.radiosity, state.direct = s.direct, state.indirect = s.indirect;
    state.unshot = s.unshot, state.irradiance = s.irradiance, state.lightGain = lightGain;
    state.transmittedDirect = s.transmittedDirect, state.transmittedIndirect = s.transmittedIndirect;
    state.raysArrived = raysArrived;
    writeStochasticCheckpoint(checkpoint.path, checkpoint.job, state);
    lastCheckpoint = std::chrono::steady_clock::now();
  };

  for (int iteration = firstIteration; iteration <= maxIterations; ++iteration) {
    // Sources: the CDF of unshot power (band average).
    std::vector<double> cdf(n);
    double total = 0;
    for (size_t e = 0; e < n; ++e) {
      total += s.unshot[e].average() * s.mesh.elements[e].area;
      cdf[e] = total;
    }
    s.stats.residual = total / emitted;
    if (s.stats.residual < options.tolerance || total <= 0) {
      if (lightGain.empty()) break;
      // The emitters' light is (all but) spent before the point lights' was
      // shot on (a faint panel beside strong lamps): shoot that now.
      shootLightGain();
      emissionFirst = false;
      --iteration;
      continue;
    }
    const size_t rays = std::max<size_t>(1000, static_cast<size_t>(double(firstRays) * total / emitted));
    const double powerPerRay = total / double(rays);
    const size_t chunks = (rays + kChunk - 1) / kChunk;
    // Chunks run in parallel a batch at a time and are merged in order: the
    // sum is deterministic and the deposits held at once stay bounded.
    constexpr size_t kBatch = 64;
    // This rank's chunks (all of them with one rank).
    const size_t ranks = size_t(cluster::size());
    std::vector<size_t> ownChunks;
    for (size_t c = size_t(cluster::rank()); c < chunks; c += ranks) ownChunks.push_back(c);
    const double unitsPerWatt = kArrivalScale / total;
    std::vector<int64_t> arrived(n * kBandCount, 0);  // fixed point, kArrivalScale per `total`
    std::vector<std::vector<Deposit>> deposits(kBatch);
    for (size_t batchStart = 0; batchStart < ownChunks.size(); batchStart += kBatch) {
      const size_t batchEnd = std::min(ownChunks.size(), batchStart + kBatch);
      arena.execute([&] {
        tbb::parallel_for(batchStart, batchEnd, [&](size_t i) {
          const size_t c = ownChunks[i];
          Pcg32 rng = sampleGenerator(options.seed, c, uint64_t(iteration) << 20 | 0x5a);
          const size_t begin = c * kChunk, end = std::min(rays, begin + kChunk);
          std::vector<Deposit> &out = deposits[i - batchStart];
          out.clear();
          out.reserve(end - begin);
          size_t source = 0;
          for (size_t r = begin; r < end; ++r) {
            // Stratify the source choice across all rays of the iteration.
            // u grows with r, so the chunk's sources come in CDF order: one
            // binary search for its first ray, then a walk forward (rays of
            // one source follow each other: its element stays in cache).
            double u = (double(r) + rng.next()) / double(rays) * total;
            if (r == begin)
              source = std::min(n - 1, size_t(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin()));
            else
              while (source + 1 < n && cdf[source] <= u) ++source;
            const Element &element = s.mesh.elements[source];
            const Vec3 &normal = s.mesh.normalOf(static_cast<uint32_t>(source));
            double a = rng.next(), b = rng.next(), d1 = rng.next(), d2 = rng.next();
            Vec3 origin;
            const auto &nodes = element.nodes;
            if (element.vertexCount == 4) {
              const Vec3 &p0 = s.mesh.nodes[nodes[0]], &p1 = s.mesh.nodes[nodes[1]], &p2 = s.mesh.nodes[nodes[2]],
                         &p3 = s.mesh.nodes[nodes[3]];
              // Planar quad: pick a triangle by area, then a uniform point in it.
              double a1 = length(cross(p1 - p0, p2 - p0)), a2 = length(cross(p2 - p0, p3 - p0));
              double b1, b2;
              if (a * (a1 + a2) < a1) {
                sampleUniformTriangle(a * (a1 + a2) / a1, b, b1, b2);
                origin = p0 * (1 - b1 - b2) + p1 * b1 + p2 * b2;
              } else {
                sampleUniformTriangle((a * (a1 + a2) - a1) / a2, b, b1, b2);
                origin = p0 * (1 - b1 - b2) + p2 * b1 + p3 * b2;
              }
            } else {
              double b1, b2;
              sampleUniformTriangle(a, b, b1, b2);
              origin =
                  s.mesh.nodes[nodes[0]] * (1 - b1 - b2) + s.mesh.nodes[nodes[1]] * b1 + s.mesh.nodes[nodes[2]] * b2;
            }
            Vec3 direction = Frame::fromNormal(normal).toWorld(sampleCosineHemisphere(d1, d2));
            Hit hit;
            if (!tracer.intersectPosition(tracer.spawnRay(origin, normal, direction), hit)) continue;  // escaped
            if (dot(hit.geometricNormal, direction) >= 0) continue;  // a back side: not in the solution
            const int32_t whole = wholeFaceElement[hit.face];
            if (whole == RadiosityMesh::kNoElement) continue;
            const uint32_t receiver = whole >= 0 ? uint32_t(whole) : s.mesh.locate(hit.face, hit.position).element;
            const Bands &colour = s.unshot[source];
            out.push_back({receiver, colour * (powerPerRay / colour.average())});
          }
        });
      });
      for (size_t i = batchStart; i < batchEnd; ++i)
        for (const Deposit &d : deposits[i - batchStart])
          for (int b = 0; b < kBandCount; ++b)
            arrived[size_t(d.element) * kBandCount + b] += std::llround(d.power[b] * unitsPerWatt);
    }
    cluster::sumOnAllRanks(arrived.data(), arrived.size());

    // The first iteration shoots all the unshot radiosity there is, the
    // emission, so what it deposits is the direct part; later ones, reflections.
    const bool direct = iteration == 1 && emissionFirst;
    for (size_t e = 0; e < n; ++e) s.unshot[e] = Bands(0.0);
    auto gainAt = [&](size_t e, const Bands &gain) {
      s.radiosity[e] += gain;
      (direct ? s.direct[e] : s.indirect[e]) += gain;
      s.unshot[e] += gain;
    };
    auto passedTo = [&](size_t e, const Bands &gain) {
      gainAt(e, gain);
      if (s.hasTransmitted()) s.transmittedIndirect[e] += gain;
    };
    for (size_t e = 0; e < n; ++e) {
      Bands power;
      for (int b = 0; b < kBandCount; ++b) power[b] = double(arrived[e * kBandCount + b]) / unitsPerWatt;
      if (power.max() <= 0) continue;
      raysArrived[e] += power.average() / powerPerRay;
      Bands irradiance = power / s.mesh.elements[e].area;
      s.irradiance[e] += irradiance;
      gainAt(e, s.reflectance[e] * irradiance);
      transmission.pass(e, irradiance, passedTo);
    }
    if (!lightGain.empty()) shootLightGain();
    s.stats.formFactorRays += rays;
    s.stats.iterations = iteration;
    // Saved before the progress report, where an interrupt stops the solve.
    if (!checkpoint.path.empty() &&
        (interruptRequested() ||
         std::chrono::duration<double>(std::chrono::steady_clock::now() - lastCheckpoint).count() >=
             checkpoint.intervalSeconds))
      saveCheckpoint(iteration);
    if (progress)
      progress({iteration, s.stats.residual, options.tolerance,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
  }
  if (!checkpoint.path.empty() && checkpoint.saveWhenDone && !interruptRequested()) saveCheckpoint(s.stats.iterations);
  // Final residual and energy balance.
  Bands unshotPower(0.0);
  s.stats.absorbedPower = Bands(0.0);
  for (size_t e = 0; e < n; ++e) {
    double a = s.mesh.elements[e].area;
    unshotPower += s.unshot[e] * a;
    s.stats.absorbedPower += s.absorptance(e) * s.irradiance[e] * a;
  }
  s.stats.residual = unshotPower.average() / emitted;
  s.stats.escapedPower = s.stats.emittedPower - s.stats.absorbedPower - unshotPower;
  s.ambient = Bands(0.0);
  if (directAtNodes) {
    // The reflected light's irradiance at the nodes, formed from the
    // elements' as nodeRadiosity would be; the display adds ρ̄·H_direct.
    std::vector<Bands> reflectedPower(n);
    for (size_t e = 0; e < n; ++e) reflectedPower[e] = (s.irradiance[e] - elementDirect[e]) * s.mesh.elements[e].area;
    // A final gather at every node (reflected_light_gather.h): where its
    // elements hold too few rays (a tessellated model's facets) within a
    // budget of rays, elsewhere (a wall's) with kGatherRaysWhereEnough; a
    // mesh too large for it (more than 4·10⁶ nodes, where 16 rays a node
    // would be over budget) takes the density estimate instead.
    Vec3 lo = s.mesh.nodes.front(), hi = lo;
    for (const Vec3 &p : s.mesh.nodes)
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)},
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    const double sceneExtent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    SparseNodeEstimate gather = [&](const std::vector<uint32_t> &nodes, bool enoughRays) {
      const auto gatherStart = std::chrono::steady_clock::now();
      const int raysPerNode = enoughRays
                                  ? kGatherRaysWhereEnough
                                  : int(std::clamp<size_t>(kGatherRays / std::max<size_t>(1, nodes.size()), 16, 32));
      std::vector<Bands> gathered =
          gatherReflectedIrradiance(tracer, s, nodes, raysPerNode, sceneExtent / 256, options.seed, options.threads);
      s.stats.formFactorRays += nodes.size() * size_t(raysPerNode);
      if (timing)
        std::fprintf(stderr, "  %-28s %.3f s (%zu nodes, %d rays each)\n", "gathering at the nodes",
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - gatherStart).count(),
                     nodes.size(), raysPerNode);
      return gathered;
    };
    if (s.mesh.nodes.size() > kGatherRays / 4) gather = nullptr;
    s.nodeIndirectIrradiance =
        reflectedIrradianceAtNodes(s, reflectedPower, raysArrived, kEnoughRays, options.threads, gather);
  }
}

}  // namespace radiant
