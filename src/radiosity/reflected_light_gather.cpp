#include "radiosity/reflected_light_gather.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "cluster/cluster.h"
#include "util/phase.h"
#include "util/random.h"
#include "util/sampling.h"

namespace radiant {

namespace {

/// The gathered values averaged over the gathered nodes within a small
/// radius that face the same way: each node's own gather has the noise of
/// its few rays, and its neighbours', a few millimetres away on the same
/// surface, saw nearly the same light. Weights (1 − d²/r²)·max(0, n·n')⁸
/// within one object: the noise falls with the neighbours' count, the blur
/// stays within the radius, and the two sides of a thin part never mix.
std::vector<Bands> smoothOverNeighbours(const RadiosityMesh &mesh, const std::vector<uint32_t> &nodes,
                                        const std::vector<Vec3> &normal, const std::vector<Bands> &gathered,
                                        double radius, int threads) {
  Vec3 lo = mesh.nodes[nodes[0]];
  for (uint32_t v : nodes) {
    const Vec3 &p = mesh.nodes[v];
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
  }
  // The gathered nodes sorted by their cell of a grid of the radius.
  struct Keyed {
    int64_t x, y, z;
    uint32_t index;
    bool operator<(const Keyed &o) const { return std::tie(x, y, z, index) < std::tie(o.x, o.y, o.z, o.index); }
  };
  auto cellOf = [&](const Vec3 &p, uint32_t index) {
    return Keyed{int64_t(std::floor((p.x - lo.x) / radius)), int64_t(std::floor((p.y - lo.y) / radius)),
                 int64_t(std::floor((p.z - lo.z) / radius)), index};
  };
  std::vector<Keyed> keyed(nodes.size());
  for (uint32_t i = 0; i < nodes.size(); ++i) keyed[i] = cellOf(mesh.nodes[nodes[i]], i);
  std::sort(keyed.begin(), keyed.end());
  std::vector<Bands> smoothed(nodes.size());
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(size_t(0), nodes.size(), [&](size_t i) {
      const Vec3 &x = mesh.nodes[nodes[i]];
      const uint32_t object = mesh.patches[mesh.nodePatch[nodes[i]]].object;
      const Keyed centre = cellOf(x, 0);
      Bands sum(0.0);
      double weights = 0;
      for (int64_t dx = -1; dx <= 1; ++dx)
        for (int64_t dy = -1; dy <= 1; ++dy)
          for (int64_t dz = -1; dz <= 1; ++dz) {
            const Keyed first{centre.x + dx, centre.y + dy, centre.z + dz, 0};
            for (auto it = std::lower_bound(keyed.begin(), keyed.end(), first);
                 it != keyed.end() && it->x == first.x && it->y == first.y && it->z == first.z; ++it) {
              const uint32_t j = it->index;
              const Vec3 offset = mesh.nodes[nodes[j]] - x;
              const double d2 = dot(offset, offset) / (radius * radius);
              const double facing = dot(normal[i], normal[j]);
              if (d2 >= 1 || facing <= 0 || mesh.patches[mesh.nodePatch[nodes[j]]].object != object) continue;
              const double f2 = facing * facing, f4 = f2 * f2;
              const double w = (1 - d2) * f4 * f4;
              sum += gathered[j] * w;
              weights += w;
            }
          }
      smoothed[i] = weights > 0 ? sum / weights : gathered[i];
    });
  });
  return smoothed;
}

}  // namespace

std::vector<Bands> gatherReflectedIrradiance(const RayTracer &tracer, const Solution &solution,
                                             const std::vector<uint32_t> &nodes, int raysPerNode,
                                             double smoothingRadius, uint64_t seed, int threads) {
  const RadiosityMesh &mesh = solution.mesh;
  std::vector<Bands> gathered(nodes.size(), Bands(0.0));
  if (nodes.empty()) return gathered;

  // Each pool's direction: the mean of its nodes' patch normals (a pool is
  // one smooth surface's nodes at one place), as node_direct_light.cpp's.
  const std::vector<uint32_t> pool = solution.nodePools();
  std::vector<Vec3> poolNormal(mesh.nodes.size());
  for (uint32_t v = 0; v < mesh.nodes.size(); ++v) poolNormal[pool[v]] += mesh.patches[mesh.nodePatch[v]].normal;
  std::vector<Vec3> normal(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) {
    const double len = length(poolNormal[pool[nodes[i]]]);
    normal[i] = len > 0 ? poolNormal[pool[nodes[i]]] / len : mesh.patches[mesh.nodePatch[nodes[i]]].normal;
  }

  // What a ray reads where it lands: the element's radiosity less its
  // emission, the light leaving it after at least one reflection (W·m⁻²).
  std::vector<Bands> reflected(solution.elementCount());
  for (size_t e = 0; e < reflected.size(); ++e) reflected[e] = solution.radiosity[e] - solution.emission[e];

  // A model's facet is its own element: found without reading its patch.
  const std::vector<int32_t> wholeFaceElement = mesh.wholeFaceElements();

  // A k × k stratified grid over the unit square, mapped to the cosine-
  // weighted hemisphere by the concentric map (which keeps the strata's areas).
  const int k = std::max(1, int(std::lround(std::sqrt(double(std::max(1, raysPerNode))))));
  const double perRay = 1.0 / double(k * k);
  const size_t ranks = size_t(cluster::size()), rank = size_t(cluster::rank());
  auto owns = [&](size_t i) { return i % ranks == rank; };

  Phase phase("gathering the reflected light at the nodes", nodes.size());
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nodes.size(), 64), [&](const tbb::blocked_range<size_t> &range) {
      phase.advance(range.size());
      for (size_t i = range.begin(); i != range.end(); ++i) {
        if (!owns(i)) continue;
        const uint32_t v = nodes[i];
        const Frame frame = Frame::fromNormal(normal[i]);
        // From a hair inside the patch (16 ε towards its centre): a node on
        // a wall's edge lies in the plane of the wall it meets, and rays from
        // there slipped through the seam (the room's corners came out 18 % dark).
        const Patch &patch = mesh.patches[mesh.nodePatch[v]];
        Vec3 centre;
        for (int c = 0; c < patch.vertexCount; ++c) centre += patch.corners[c];
        centre = centre / patch.vertexCount;
        const Vec3 inward = centre - mesh.nodes[v];
        const double inwardLength = length(inward);
        const Vec3 origin =
            inwardLength > 0 ? mesh.nodes[v] + inward * (std::min(inwardLength, 16 * tracer.epsilon()) / inwardLength)
                             : mesh.nodes[v];
        Pcg32 rng = sampleGenerator(seed, v, 0x6a7468);
        Bands sum(0.0);
        for (int a = 0; a < k; ++a)
          for (int b = 0; b < k; ++b) {
            const Vec3 direction = frame.toWorld(sampleCosineHemisphere((a + rng.next()) / k, (b + rng.next()) / k));
            Hit hit;
            if (!tracer.intersectPosition(tracer.spawnRay(origin, normal[i], direction), hit)) continue;
            // A back side (of a one-sided face) holds no light in the solution.
            if (dot(hit.geometricNormal, direction) >= 0) continue;
            const int32_t whole = wholeFaceElement[hit.face];
            if (whole == RadiosityMesh::kNoElement) continue;  // a face left out of the mesh (hidden)
            sum += reflected[whole >= 0 ? uint32_t(whole) : mesh.locate(hit.face, hit.position).element];
          }
        gathered[i] = sum * perRay;
      }
    });
  });
  std::vector<size_t> all(nodes.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  cluster::shareOwnedEntries(gathered, all, owns);
  if (smoothingRadius <= 0) return gathered;
  return smoothOverNeighbours(mesh, nodes, normal, gathered, smoothingRadius, threads);
}

}  // namespace radiant
