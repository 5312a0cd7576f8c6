#include "radiosity/cluster_tree.h"

#include <algorithm>

namespace radiant {

namespace {

constexpr uint32_t kLeafPatches = 4;

struct Builder {
  const RadiosityMesh &mesh;
  ClusterTree &tree;
  std::vector<Box3> patchBounds;
  std::vector<Vec3> patchCentres;

  Vec3 centroid(const Patch &p) const {
    Vec3 c;
    for (int k = 0; k < p.vertexCount; ++k) c += p.corners[k];
    return c / double(p.vertexCount);
  }

  int32_t build(uint32_t first, uint32_t count, int32_t parent) {
    const int32_t index = static_cast<int32_t>(tree.clusters.size());
    tree.clusters.push_back({});
    Cluster c;
    c.first = first;
    c.count = count;
    c.parent = parent;
    double weighted = 0;
    for (uint32_t i = first; i < first + count; ++i) {
      const uint32_t p = tree.order[i];
      c.bounds.extend(patchBounds[p]);
      c.area += mesh.patches[p].area;
      c.centre += patchCentres[p] * mesh.patches[p].area;
      weighted += mesh.patches[p].area;
    }
    c.centre = weighted > 0 ? c.centre / weighted : (c.bounds.lo + c.bounds.hi) * 0.5;

    // Own patches: too large for a child along some axis.
    const Vec3 extent = c.bounds.hi - c.bounds.lo;
    const double size = std::max({extent.x, extent.y, extent.z});
    auto large = [&](uint32_t p) {
      const Vec3 e = patchBounds[p].hi - patchBounds[p].lo;
      for (int k = 0; k < 3; ++k)
        if (extent[k] > 1e-6 * size && e[k] > 0.5 * extent[k]) return true;
      return false;
    };
    auto begin = tree.order.begin() + first, end = begin + count;
    uint32_t own =
        count <= kLeafPatches ? count : static_cast<uint32_t>(std::stable_partition(begin, end, large) - begin);
    if (count - own <= kLeafPatches) own = count;
    c.ownCount = own;
    tree.clusters[index] = c;
    if (own == count) return index;

    // The rest: median split along the longest axis of their centres.
    Box3 centres;
    for (auto it = begin + own; it != end; ++it) centres.extend(patchCentres[*it]);
    const Vec3 spread = centres.hi - centres.lo;
    const int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
    const uint32_t rest = count - own, half = rest / 2;
    std::nth_element(begin + own, begin + own + half, end, [&](uint32_t a, uint32_t b) {
      const double ca = patchCentres[a][axis], cb = patchCentres[b][axis];
      return ca < cb || (ca == cb && a < b);
    });
    const int32_t left = build(first + own, half, index);
    const int32_t right = build(first + own + half, rest - half, index);
    tree.clusters[index].left = left;
    tree.clusters[index].right = right;
    return index;
  }
};

}  // namespace

ClusterTree buildClusterTree(const RadiosityMesh &mesh) {
  ClusterTree tree;
  const uint32_t patches = static_cast<uint32_t>(mesh.patches.size());
  if (patches == 0) return tree;
  Builder b{mesh, tree, {}, {}};
  b.patchBounds.resize(patches);
  b.patchCentres.resize(patches);
  for (uint32_t p = 0; p < patches; ++p) {
    const Patch &patch = mesh.patches[p];
    for (int k = 0; k < patch.vertexCount; ++k) b.patchBounds[p].extend(patch.corners[k]);
    b.patchCentres[p] = b.centroid(patch);
  }
  tree.order.resize(patches);
  for (uint32_t p = 0; p < patches; ++p) tree.order[p] = p;
  tree.clusters.reserve(patches);
  b.build(0, patches, -1);
  tree.positionOf.resize(patches);
  tree.ownerOf.resize(patches);
  for (uint32_t i = 0; i < patches; ++i) tree.positionOf[tree.order[i]] = i;
  for (uint32_t c = 0; c < tree.clusters.size(); ++c) {
    const Cluster &cluster = tree.clusters[c];
    for (uint32_t i = cluster.first; i < cluster.first + cluster.ownCount; ++i) tree.ownerOf[tree.order[i]] = c;
  }
  return tree;
}

}  // namespace radiant
