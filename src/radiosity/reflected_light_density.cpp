#include "radiosity/reflected_light_density.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

namespace radiant {

namespace {

/// Six soft directions, ±x, ±y, ±z: a unit normal n gives direction k the
/// weight max(0, ±n_axis)², and the six sum to |n|² = 1. An element counts
/// in a node's estimate by the overlap of their weights, so surfaces facing
/// away from each other (the two sides of a thin panel) never mix, and the
/// facets of a curved model blend smoothly.
constexpr int kDirections = 6;
using DirectionWeights = std::array<double, kDirections>;

DirectionWeights directionWeights(const Vec3 &n) {
  auto sq = [](double v) { return v > 0 ? v * v : 0.0; };
  return {sq(n.x), sq(-n.x), sq(n.y), sq(-n.y), sq(n.z), sq(-n.z)};
}

/// The ladder of neighbourhoods: cells of 1/256 of the scene's extent,
/// doubling to 1/8 (the default element size).
constexpr int kLevels = 6;
constexpr double kFinestCell = 1.0 / 256;

struct CellKey {
  int32_t x, y, z;
  uint32_t object;
  bool operator==(const CellKey &o) const { return x == o.x && y == o.y && z == o.z && object == o.object; }
};

struct CellKeyHash {
  size_t operator()(const CellKey &k) const {
    uint64_t h = uint64_t(uint32_t(k.x)) * 0x9E3779B97F4A7C15ull;
    h ^= (uint64_t(uint32_t(k.y)) + 0x7F4A7C15ull + (h << 6) + (h >> 2)) * 0xBF58476D1CE4E5B9ull;
    h ^= (uint64_t(uint32_t(k.z)) + 0x94D049BBull + (h << 6) + (h >> 2)) * 0x94D049BB133111EBull;
    h ^= uint64_t(k.object) + (h << 6) + (h >> 2);
    return size_t(h ^ (h >> 31));
  }
};

/// What landed in one cell, by direction.
struct CellSums {
  std::array<Bands, kDirections> power{};
  std::array<double, kDirections> area{}, rays{};
};

/// The deposits of one level: sums per cell and object, read back with
/// trilinear (tent) weights around a point, so the estimate varies smoothly.
class DepositGrid {
 public:
  DepositGrid(const Vec3 &origin, double cell) : origin_(origin), cell_(cell) {}

  void add(uint32_t object, const Vec3 &centre, const DirectionWeights &weights, const Bands &power, double area,
           double rays) {
    const Vec3 q = (centre - origin_) / cell_;
    CellSums &sums = cells_[{int32_t(std::floor(q.x)), int32_t(std::floor(q.y)), int32_t(std::floor(q.z)), object}];
    for (int k = 0; k < kDirections; ++k) {
      if (weights[k] <= 0) continue;
      sums.power[k] += power * weights[k];
      sums.area[k] += area * weights[k];
      sums.rays[k] += rays * weights[k];
    }
  }

  /// The tent-weighted sums around x for a surface facing `weights`.
  void gather(uint32_t object, const Vec3 &x, const DirectionWeights &weights, Bands &power, double &area,
              double &rays) const {
    power = Bands(0.0), area = 0, rays = 0;
    // Cell centres lie at (i + ½)·cell: the eight around x and x's place among them.
    const Vec3 q = (x - origin_) / cell_ - Vec3(0.5, 0.5, 0.5);
    const int32_t ix = int32_t(std::floor(q.x)), iy = int32_t(std::floor(q.y)), iz = int32_t(std::floor(q.z));
    const double fx = q.x - ix, fy = q.y - iy, fz = q.z - iz;
    for (int d = 0; d < 8; ++d) {
      const int dx = d & 1, dy = (d >> 1) & 1, dz = d >> 2;
      const double w = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) * (dz ? fz : 1 - fz);
      if (w <= 0) continue;
      auto it = cells_.find({ix + dx, iy + dy, iz + dz, object});
      if (it == cells_.end()) continue;
      for (int k = 0; k < kDirections; ++k) {
        const double wk = w * weights[k];
        if (wk <= 0) continue;
        power += it->second.power[k] * wk;
        area += it->second.area[k] * wk;
        rays += it->second.rays[k] * wk;
      }
    }
  }

 private:
  Vec3 origin_;
  double cell_;
  std::unordered_map<CellKey, CellSums, CellKeyHash> cells_;
};

}  // namespace

std::vector<Bands> reflectedIrradianceAtNodes(const Solution &solution, const std::vector<Bands> &power,
                                              const std::vector<double> &rays, double enoughRays, int threads,
                                              const SparseNodeEstimate &estimateSparse) {
  const RadiosityMesh &mesh = solution.mesh;
  const size_t nodeCount = mesh.nodes.size();
  std::vector<Bands> atNodes(nodeCount, Bands(0.0));
  if (nodeCount == 0) return atNodes;

  // Each pool's elements: their power, area and rays, summed at its head
  // (its first node), which is the usual node value's sum.
  const std::vector<uint32_t> pool = solution.nodePools();
  std::vector<Bands> powerAround(nodeCount, Bands(0.0));
  std::vector<double> areaAround(nodeCount, 0.0), raysAround(nodeCount, 0.0);
  std::vector<Vec3> normalSum(nodeCount);
  for (uint32_t e = 0; e < mesh.elements.size(); ++e) {
    const Element &element = mesh.elements[e];
    for (int k = 0; k < element.vertexCount; ++k) {
      const uint32_t head = pool[element.nodes[k]];
      powerAround[head] += power[e];
      areaAround[head] += element.area;
      raysAround[head] += rays[e];
    }
  }
  for (uint32_t v = 0; v < nodeCount; ++v) normalSum[pool[v]] += mesh.patches[mesh.nodePatch[v]].normal;

  // The heads whose own elements hold too few rays, and their objects.
  std::vector<uint32_t> sparse;
  std::vector<bool> objectIsSparse;
  for (uint32_t v = 0; v < nodeCount; ++v) {
    if (pool[v] != v) continue;
    if (areaAround[v] > 0) atNodes[v] = powerAround[v] / areaAround[v];
    if (raysAround[v] >= enoughRays) continue;
    sparse.push_back(v);
    const uint32_t object = mesh.patches[mesh.nodePatch[v]].object;
    if (object >= objectIsSparse.size()) objectIsSparse.resize(object + 1, false);
    objectIsSparse[object] = true;
  }

  if (estimateSparse) {
    // The estimator takes every node: those with too few rays, and those
    // with enough, whose own elements' mean misses what varies within them
    // (a room's corners, the floor beside a model).
    std::vector<uint32_t> dense;
    for (uint32_t v = 0; v < nodeCount; ++v)
      if (pool[v] == v && raysAround[v] >= enoughRays) dense.push_back(v);
    for (const bool enough : {false, true}) {
      const std::vector<uint32_t> &nodes = enough ? dense : sparse;
      if (nodes.empty()) continue;
      const std::vector<Bands> estimates = estimateSparse(nodes, enough);
      for (size_t i = 0; i < nodes.size(); ++i) atNodes[nodes[i]] = estimates[i];
    }
  } else if (!sparse.empty()) {
    // The ladder of grids over the objects that need them.
    Vec3 lo = mesh.nodes[0], hi = mesh.nodes[0];
    for (const Vec3 &p : mesh.nodes) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-9});
    std::vector<DepositGrid> levels;
    for (int l = 0; l < kLevels; ++l) levels.emplace_back(lo, extent * kFinestCell * double(1 << l));
    for (uint32_t e = 0; e < mesh.elements.size(); ++e) {
      const Patch &patch = mesh.patchOf(e);
      if (patch.object >= objectIsSparse.size() || !objectIsSparse[patch.object]) continue;
      const DirectionWeights weights = directionWeights(patch.normal);
      for (DepositGrid &grid : levels)
        grid.add(patch.object, mesh.elements[e].centre, weights, power[e], mesh.elements[e].area, rays[e]);
    }
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
      tbb::parallel_for(size_t(0), sparse.size(), [&](size_t i) {
        const uint32_t v = sparse[i];
        const uint32_t object = mesh.patches[mesh.nodePatch[v]].object;
        const double len = length(normalSum[v]);
        const DirectionWeights weights =
            directionWeights(len > 0 ? normalSum[v] / len : mesh.patches[mesh.nodePatch[v]].normal);
        for (const DepositGrid &grid : levels) {
          Bands p;
          double area, n;
          grid.gather(object, mesh.nodes[v], weights, p, area, n);
          if (area > 0) atNodes[v] = p / area;
          if (n >= enoughRays) break;
        }
      });
    });
  }

  for (uint32_t v = 0; v < nodeCount; ++v) atNodes[v] = atNodes[pool[v]];
  for (const RadiosityMesh::TVertex &t : mesh.tVertices)
    atNodes[t.node] = atNodes[t.edgeStart] * (1.0 - t.t) + atNodes[t.edgeEnd] * double(t.t);
  return atNodes;
}

}  // namespace radiant
