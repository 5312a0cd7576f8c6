// RadiosityMesh::addCrossPatchTVertices: where two patches of one smooth
// surface meet with different lattices (the pieces of a cut face, a wall's
// tree beside another's, a model's facets split unevenly), a node of one
// lies inside an element edge of the other. Its value must then be that
// edge's interpolation, or the display cracks along the seam: these are the
// T-vertices across patches (within a patch's tree, rebuildElementsFromTrees
// finds its own).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "mesh/mesh.h"

namespace radiant {

void RadiosityMesh::addCrossPatchTVertices() {
  if (patches.size() < 2 || elements.empty()) return;
  // Element edges on their patch's boundary, binned on a grid by their boxes.
  struct Edge {
    uint32_t start, end, patch;
    double length;
  };
  std::vector<Edge> edges;
  for (const Element &e : elements) {
    const Patch &p = patches[e.patch];
    // A patch meshed as one element (a model's facet): every edge is the patch's.
    const bool whole = p.elementCount == 1;
    for (int k = 0; k < e.vertexCount; ++k) {
      const uint32_t a = e.nodes[k], b = e.nodes[(k + 1) % e.vertexCount];
      if (whole) {
        edges.push_back({a, b, e.patch, length(nodes[b] - nodes[a])});
        continue;
      }
      // On the boundary: both ends on one edge line of the patch's polygon.
      for (int v = 0; v < p.vertexCount; ++v) {
        const Vec3 &c0 = p.corners[v], &c1 = p.corners[(v + 1) % p.vertexCount];
        const Vec3 dir = c1 - c0;
        const double l2 = dot(dir, dir), tol = 1e-9 * std::sqrt(l2);
        auto off = [&](const Vec3 &x) { return length(cross(x - c0, dir)) / std::sqrt(l2); };
        if (l2 > 0 && off(nodes[a]) <= tol && off(nodes[b]) <= tol) {
          edges.push_back({a, b, e.patch, length(nodes[b] - nodes[a])});
          break;
        }
      }
    }
  }
  if (edges.empty()) return;
  Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  double mean = 0;
  for (const Vec3 &x : nodes)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], x[k]), hi[k] = std::max(hi[k], x[k]);
  for (const Edge &e : edges) mean += e.length;
  const double cell = std::max(mean / double(edges.size()), 1e-9);
  auto key = [&](const Vec3 &x) {
    return std::array<int64_t, 3>{std::llround(std::floor((x.x - lo.x) / cell)),
                                  std::llround(std::floor((x.y - lo.y) / cell)),
                                  std::llround(std::floor((x.z - lo.z) / cell))};
  };
  // A cell's hash; two cells sharing one only add candidates, which the
  // geometric test below rejects.
  auto cellHash = [](const std::array<int64_t, 3> &k) {
    const uint64_t h = uint64_t(k[0]) * 0x9E3779B97F4A7C15ull ^ uint64_t(k[1]) * 0xC2B2AE3D27D4EB4Full ^
                       uint64_t(k[2]) * 0x165667B19E3779F9ull;
    return h ^ (h >> 29);
  };
  // The cells each edge passes through: walked in steps that advance at most
  // one cell along every axis, each step adding the box of its two ends'
  // cells (a point of the segment between them lies in that box, the cell
  // index being monotone along each axis). The box of the whole edge grew
  // as the cube of a long diagonal edge's length: a 1 km edge over a model
  // of millimetre facets would have asked for 10¹⁸ cells.
  auto cellsOf = [&](size_t i, std::vector<uint64_t> &out) {
    out.clear();
    const Vec3 &a = nodes[edges[i].start], &b = nodes[edges[i].end];
    const auto ka = key(a), kb = key(b);
    int64_t steps = 1;
    for (int k = 0; k < 3; ++k) steps = std::max(steps, std::abs(kb[k] - ka[k]));
    auto previous = ka;
    for (int64_t step = 1; step <= steps; ++step) {
      const auto next = step == steps ? kb : key(a + (b - a) * (double(step) / double(steps)));
      for (int64_t x = std::min(previous[0], next[0]); x <= std::max(previous[0], next[0]); ++x)
        for (int64_t y = std::min(previous[1], next[1]); y <= std::max(previous[1], next[1]); ++y)
          for (int64_t z = std::min(previous[2], next[2]); z <= std::max(previous[2], next[2]); ++z)
            out.push_back(cellHash({x, y, z}));
      previous = next;
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  };
  // The edges of each cell, as a bucket table laid out flat (bucketStart,
  // bucketEdges; edges in index order within a bucket): a hash map of
  // vectors made a million small allocations, seconds on a 10⁶-triangle model.
  // Walked once, in fixed blocks of edges, each block's cells kept in edge
  // order, then laid out block after block: the same entries whatever the threads.
  constexpr size_t kBlock = 8192;
  std::vector<std::vector<uint64_t>> blockCells((edges.size() + kBlock - 1) / kBlock);
  std::vector<size_t> firstEntry(edges.size() + 1, 0);  // per edge, its start within its block first
  tbb::parallel_for(size_t(0), blockCells.size(), [&](size_t block) {
    std::vector<uint64_t> cells;
    for (size_t i = block * kBlock; i < std::min(edges.size(), (block + 1) * kBlock); ++i) {
      cellsOf(i, cells);
      blockCells[block].insert(blockCells[block].end(), cells.begin(), cells.end());
      firstEntry[i + 1] = cells.size();
    }
  });
  for (size_t i = 0; i < edges.size(); ++i) firstEntry[i + 1] += firstEntry[i];
  const size_t entries = firstEntry.back();
  std::vector<uint64_t> entryHash;
  entryHash.reserve(entries);
  for (std::vector<uint64_t> &cells : blockCells) {
    entryHash.insert(entryHash.end(), cells.begin(), cells.end());
    std::vector<uint64_t>().swap(cells);
  }
  size_t buckets = 1;
  while (buckets < entries) buckets *= 2;
  std::vector<uint32_t> bucketStart(buckets + 1, 0);
  for (const uint64_t h : entryHash) ++bucketStart[(h & (buckets - 1)) + 1];
  for (size_t b = 0; b < buckets; ++b) bucketStart[b + 1] += bucketStart[b];
  std::vector<uint32_t> fill(bucketStart.begin(), bucketStart.end() - 1);
  std::vector<std::pair<uint64_t, uint32_t>> bucketEdges(entries);  // (cell hash, edge)
  for (size_t i = 0; i < edges.size(); ++i)
    for (size_t entry = firstEntry[i]; entry < firstEntry[i + 1]; ++entry) {
      const uint64_t h = entryHash[entry];
      bucketEdges[fill[h & (buckets - 1)]++] = {h, uint32_t(i)};
    }
  // Each node's T-vertex (the first edge of its cell it lies inside), found in parallel, gathered in node order.
  constexpr uint32_t kNone = UINT32_MAX;
  std::vector<std::pair<uint32_t, float>> onEdge(nodes.size(), {kNone, 0.0f});
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, uint32_t(nodes.size()), 4096), [&](const auto &range) {
    for (uint32_t v = range.begin(); v < range.end(); ++v) {
      if (!nodeOnCut.empty() && nodeOnCut[v]) continue;
      const Patch &pv = patches[nodePatch[v]];
      const auto k = key(nodes[v]);
      const uint64_t h = cellHash(k);
      const size_t bucket = h & (buckets - 1);
      for (uint32_t j = bucketStart[bucket]; j < bucketStart[bucket + 1]; ++j) {
        if (bucketEdges[j].first != h) continue;
        const uint32_t edge = bucketEdges[j].second;
        const Edge &e = edges[edge];
        if (e.patch == nodePatch[v]) continue;
        const Patch &pe = patches[e.patch];
        if (pe.material != pv.material) continue;
        const Vec3 &a = nodes[e.start], &b = nodes[e.end];
        const Vec3 d = b - a;
        const double t = dot(nodes[v] - a, d) / (e.length * e.length);
        if (!(t > 1e-6 && t < 1 - 1e-6)) continue;
        if (length(nodes[v] - (a + d * t)) > 1e-7 * e.length) continue;
        // One smooth surface: the patches' normals within 2°, or (a tessellated
        // model's facets) the node's shading normal within 2° of the edge's there.
        if (dot(pe.normal, pv.normal) <= kSmoothSurfaceCosine) {
          if (nodeShadingNormals.empty()) continue;
          const Vec3 ends = toVec3(nodeShadingNormals[e.start]) * (1 - t) + toVec3(nodeShadingNormals[e.end]) * t;
          const double len = length(ends);
          if (!(len > 0) || toVec3(nodeShadingNormals[e.start]) == Vec3{} ||
              toVec3(nodeShadingNormals[e.end]) == Vec3{})
            continue;
          const Vec3 there = ends / len;
          if (!sameShadingNormal(nodeShadingNormals[v], {float(there.x), float(there.y), float(there.z)})) continue;
        }
        if ((!nodeOnCut.empty() && (nodeOnCut[e.start] || nodeOnCut[e.end]))) continue;
        onEdge[v] = {edge, float(t)};
        break;
      }
    }
  });
  std::vector<std::pair<double, TVertex>> found;
  for (uint32_t v = 0; v < nodes.size(); ++v)
    if (onEdge[v].first != kNone) {
      const Edge &e = edges[onEdge[v].first];
      found.push_back({e.length, {v, e.start, e.end, onEdge[v].second}});
    }
  for (const TVertex &t : tVertices) found.push_back({length(nodes[t.edgeEnd] - nodes[t.edgeStart]), t});
  // Coarse to fine: an edge's ends are final before a node inside it is set from them.
  std::stable_sort(found.begin(), found.end(), [](const auto &a, const auto &b) { return a.first > b.first; });
  tVertices.clear();
  for (const auto &[length, t] : found) tVertices.push_back(t);
}

}  // namespace radiant
