#include "radiosity/direct_refinement.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "cluster/cluster.h"

namespace radiant {

DirectLightField::Key DirectLightField::keyOf(uint32_t patch, const Vec3 &p) {
  Key k{patch, 0, 0, 0};
  std::memcpy(&k.x, &p.x, 8);
  std::memcpy(&k.y, &p.y, 8);
  std::memcpy(&k.z, &p.z, 8);
  return k;
}

size_t DirectLightField::KeyHash::operator()(const Key &k) const {
  uint64_t h = k.patch * 0x9E3779B97F4A7C15ULL;
  for (uint64_t v : {k.x, k.y, k.z}) h = (h ^ v) * 0xff51afd7ed558ccdULL, h ^= h >> 32;
  return static_cast<size_t>(h);
}

bool DirectLightField::has(uint32_t patch, const Vec3 &position) const {
  return values_.count(keyOf(patch, position)) > 0;
}

const Bands &DirectLightField::at(uint32_t patch, const Vec3 &position) const {
  auto it = values_.find(keyOf(patch, position));
  if (it == values_.end()) throw std::logic_error("direct light asked at a point never evaluated");
  return it->second;
}

void DirectLightField::evaluate(const RadiosityMesh &mesh, const std::vector<std::pair<uint32_t, Vec3>> &points,
                                int threads) {
  std::vector<std::pair<uint32_t, Vec3>> missing;
  for (const auto &[patch, p] : points) {
    auto [it, inserted] = values_.try_emplace(keyOf(patch, p), Bands(0.0));
    if (inserted) missing.push_back({patch, p});
  }
  std::vector<Bands> results(missing.size());
  // With several MPI ranks each evaluates every N-th point, and they share
  // the values (bit for bit: cluster::shareOwnedEntries).
  const size_t ranks = size_t(cluster::size()), rank = size_t(cluster::rank());
  auto owns = [&](size_t i) { return i % ranks == rank; };
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(size_t(0), missing.size(), [&](size_t i) {
      if (!owns(i)) return;
      const Patch &patch = mesh.patches[missing[i].first];
      // A point on the patch's boundary may lie in the plane of a wall that
      // stands there; the light it receives is the limit from inside the
      // patch, so evaluate a hair's breadth towards the patch's interior.
      Vec3 centre;
      for (int k = 0; k < patch.vertexCount; ++k) centre += patch.corners[k];
      centre = centre / patch.vertexCount;
      const Vec3 x = missing[i].second + (centre - missing[i].second) * 1e-7;
      results[i] = direct_.irradiance(x, patch.normal);
    });
  });
  if (cluster::distributed()) {
    std::vector<size_t> all(missing.size());
    for (size_t i = 0; i < all.size(); ++i) all[i] = i;
    cluster::shareOwnedEntries(results, all, owns);
  }
  for (size_t i = 0; i < missing.size(); ++i) values_[keyOf(missing[i].first, missing[i].second)] = results[i];
}

bool DirectLightField::cornersOnly(const MeshTreeNode &node) const {
  return smallestSplit_ > 0 && node.longestEdge() < 2 * smallestSplit_;
}

void DirectLightField::testPoints(const MeshTreeNode &node, std::vector<Vec3> &out, bool cornersOnly) {
  out.clear();
  for (int k = 0; k < node.vertexCount; ++k) out.push_back(node.corners[k]);
  if (cornersOnly) return;
  const auto children = childCorners(node);
  if (node.vertexCount == 4) {
    // Children (0,0), (1,0), (1,1), (0,1): child 0 holds m01, the centre, m30; child 2 m12, m23.
    out.push_back(children[0][1]);  // m01
    out.push_back(children[1][2]);  // m12
    out.push_back(children[2][3]);  // m23
    out.push_back(children[0][3]);  // m30
    out.push_back(children[0][2]);  // centre
  } else {
    out.push_back(children[3][0]);  // mab
    out.push_back(children[3][1]);  // mbc
    out.push_back(children[3][2]);  // mac
  }
}

Bands DirectLightField::nodeAverage(const MeshTreeNode &node) const {
  thread_local std::vector<Vec3> p;
  Bands sum(0.0);
  if (cornersOnly(node)) {
    for (int k = 0; k < node.vertexCount; ++k) sum += at(node.patch, node.corners[k]);
    return sum / double(node.vertexCount);
  }
  testPoints(node, p);
  if (node.vertexCount == 4) {
    for (int k = 0; k < 4; ++k) sum += at(node.patch, p[k]) + at(node.patch, p[4 + k]) * 4.0;
    sum += at(node.patch, p[8]) * 16.0;
    return sum / 36.0;
  }
  for (int k = 3; k < 6; ++k) sum += at(node.patch, p[k]);
  return sum / 3.0;
}

double DirectLightField::interpolationError(const MeshTreeNode &node, const Bands &reflectance) const {
  thread_local std::vector<Vec3> p;
  testPoints(node, p);
  const uint32_t patch = node.patch;
  auto error = [&](const Bands &exact, const Bands &interpolated) {
    double e = 0;
    for (int b = 0; b < kBandCount; ++b) e = std::max(e, reflectance[b] * std::abs(exact[b] - interpolated[b]));
    return e;
  };
  const int n = node.vertexCount;
  double worst = 0;
  if (n == 4) {
    for (int k = 0; k < 4; ++k)
      worst = std::max(worst, error(at(patch, p[4 + k]), (at(patch, p[k]) + at(patch, p[(k + 1) % 4])) * 0.5));
    worst = std::max(
        worst, error(at(patch, p[8]), (at(patch, p[0]) + at(patch, p[1]) + at(patch, p[2]) + at(patch, p[3])) * 0.25));
  } else {
    // mab, mbc, mac against their edges' ends.
    const int ends[3][2] = {{0, 1}, {1, 2}, {0, 2}};
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, error(at(patch, p[3 + k]), (at(patch, p[ends[k][0]]) + at(patch, p[ends[k][1]])) * 0.5));
  }
  return worst;
}

std::vector<Bands> directRefinementWeights(const Scene &scene, const RadiosityMesh &mesh) {
  std::vector<Bands> weights(mesh.patches.size());
  for (uint32_t p = 0; p < mesh.patches.size(); ++p) {
    const Material &m = scene.materials[mesh.patches[p].material];
    weights[p] = m.kind == MaterialKind::Lambertian || m.kind == MaterialKind::Glossy ? m.diffuse : Bands(0.0);
    for (int b = 0; b < kBandCount; ++b) weights[p][b] = std::max(weights[p][b], m.transmittance[b]);
  }
  return weights;
}

double meanFirstBounce(const RadiosityMesh &mesh, DirectLightField &field, const std::vector<Bands> &weights,
                       int threads, bool weightedOnly) {
  auto counts = [&](const MeshTreeNode &t) { return t.isLeaf() && (!weightedOnly || weights[t.patch].max() > 0); };
  std::vector<std::pair<uint32_t, Vec3>> points;
  std::vector<Vec3> nodePoints;
  for (const MeshTreeNode &t : mesh.tree) {
    if (!counts(t)) continue;
    field.testPointsOf(t, nodePoints);
    for (const Vec3 &p : nodePoints) points.push_back({t.patch, p});
  }
  field.evaluate(mesh, points, threads);
  double sum = 0, area = 0;
  for (const MeshTreeNode &t : mesh.tree) {
    if (!counts(t)) continue;
    sum += (weights[t.patch] * field.nodeAverage(t)).max() * t.area;
    area += t.area;
  }
  return area > 0 ? sum / area : 0;
}

size_t refineForDirectLight(RadiosityMesh &mesh, const std::vector<Bands> &patchReflectance, DirectLightField &field,
                            const DirectRefinementOptions &options) {
  std::vector<uint32_t> candidates;
  size_t leaves = 0;
  for (uint32_t n = 0; n < mesh.tree.size(); ++n) {
    if (!mesh.tree[n].isLeaf()) continue;
    ++leaves;
    if (patchReflectance[mesh.tree[n].patch].max() > 0) candidates.push_back(n);
  }
  field.setSmallestSplit(options.minimumEdge);
  size_t split = 0;
  std::vector<std::pair<uint32_t, Vec3>> points;
  std::vector<Vec3> nodePoints;
  while (!candidates.empty()) {
    points.clear();
    for (uint32_t n : candidates) {
      field.testPointsOf(mesh.tree[n], nodePoints);
      for (const Vec3 &p : nodePoints) points.push_back({mesh.tree[n].patch, p});
    }
    field.evaluate(mesh, points, options.threads);
    std::vector<uint32_t> next;
    for (uint32_t n : candidates) {
      const MeshTreeNode &node = mesh.tree[n];
      if (field.cornersOnly(node)) continue;  // too small to split
      if (field.interpolationError(node, patchReflectance[node.patch]) <= options.tolerance) continue;
      if (leaves + 3 > options.maxElements) break;
      splitTreeNode(mesh, n);
      leaves += 3;
      ++split;
      for (int c = 0; c < 4; ++c) next.push_back(static_cast<uint32_t>(mesh.tree[n].children[c]));
    }
    candidates = std::move(next);
  }
  // Every leaf's test points are known: their averages and the nodes' values can be read.
  rebuildElementsFromTrees(mesh);
  return split;
}

}  // namespace radiant
