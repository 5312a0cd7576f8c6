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
  // The edges of each cell, as a bucket table laid out flat (bucketStart,
  // bucketEdges; edges in index order within a bucket): a hash map of
  // vectors made a million small allocations, seconds on a 10⁶-triangle model.
  std::vector<std::array<int64_t, 6>> cellRange(edges.size());  // lo and hi cell of each edge's box
  std::vector<uint32_t> cellCount(edges.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, edges.size(), 8192), [&](const auto &range) {
    for (size_t i = range.begin(); i < range.end(); ++i) {
      const auto ka = key(nodes[edges[i].start]), kb = key(nodes[edges[i].end]);
      auto &r = cellRange[i];
      uint64_t count = 1;
      for (int k = 0; k < 3; ++k) {
        r[k] = std::min(ka[k], kb[k]), r[3 + k] = std::max(ka[k], kb[k]);
        count *= uint64_t(r[3 + k] - r[k] + 1);
      }
      cellCount[i] = uint32_t(std::min<uint64_t>(count, UINT32_MAX));
    }
  });
  size_t entries = 0;
  for (uint32_t c : cellCount) entries += c;
  size_t buckets = 1;
  while (buckets < entries) buckets *= 2;
  std::vector<uint32_t> bucketStart(buckets + 1, 0);
  std::vector<uint64_t> entryHash;
  entryHash.reserve(entries);
  auto forEachCell = [&](size_t i, auto &&visit) {
    const auto &r = cellRange[i];
    for (int64_t x = r[0]; x <= r[3]; ++x)
      for (int64_t y = r[1]; y <= r[4]; ++y)
        for (int64_t z = r[2]; z <= r[5]; ++z) visit(cellHash({x, y, z}));
  };
  for (size_t i = 0; i < edges.size(); ++i)
    forEachCell(i, [&](uint64_t h) {
      entryHash.push_back(h);
      ++bucketStart[(h & (buckets - 1)) + 1];
    });
  for (size_t b = 0; b < buckets; ++b) bucketStart[b + 1] += bucketStart[b];
  std::vector<uint32_t> fill(bucketStart.begin(), bucketStart.end() - 1);
  std::vector<std::pair<uint64_t, uint32_t>> bucketEdges(entries);  // (cell hash, edge)
  for (size_t i = 0, entry = 0; i < edges.size(); ++i)
    for (uint32_t c = 0; c < cellCount[i]; ++c, ++entry) {
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
