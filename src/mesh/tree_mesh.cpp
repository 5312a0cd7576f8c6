// Meshes whose patches are subdivision trees: built uniformly, refined
// adaptively, and turned into elements, shared nodes and T-vertices.
//
// Quads split at their bilinear midpoints into children (0,0), (1,0), (1,1),
// (0,1); triangles into the corners at vertex 0, 1, 2 and the middle
// triangle — the layout RadiosityMesh::locateInTree descends.
#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <functional>
#include <map>
#include <tuple>

#include "mesh/mesh.h"
#include "util/error.h"
#include "util/timing.h"

namespace radiant {

namespace {

/// Exact bit pattern of a position: shared corners are computed by the same
/// arithmetic from the same parents, so equal corners have equal bits.
struct PositionKey {
  uint64_t x, y, z;
  bool operator<(const PositionKey &o) const { return std::tie(x, y, z) < std::tie(o.x, o.y, o.z); }
};
PositionKey keyOf(const Vec3 &p) {
  PositionKey k;
  std::memcpy(&k.x, &p.x, 8);
  std::memcpy(&k.y, &p.y, 8);
  std::memcpy(&k.z, &p.z, 8);
  return k;
}

double polygonArea(const std::array<Vec3, 4> &c, int count) {
  double area = 0;
  for (int k = 1; k + 1 < count; ++k) area += 0.5 * length(cross(c[k] - c[0], c[k + 1] - c[0]));
  return area;
}

}  // namespace

std::array<std::array<Vec3, 4>, 4> childCorners(const MeshTreeNode &node) {
  const auto &c = node.corners;
  auto mid = [](const Vec3 &a, const Vec3 &b) { return (a + b) * 0.5; };
  if (node.vertexCount == 4) {
    Vec3 m01 = mid(c[0], c[1]), m12 = mid(c[1], c[2]), m23 = mid(c[2], c[3]), m30 = mid(c[3], c[0]);
    Vec3 centre = mid(m01, m23);
    return {{{c[0], m01, centre, m30}, {m01, c[1], m12, centre}, {centre, m12, c[2], m23}, {m30, centre, m23, c[3]}}};
  }
  Vec3 mab = mid(c[0], c[1]), mbc = mid(c[1], c[2]), mac = mid(c[0], c[2]);
  return {{{c[0], mab, mac, Vec3{}}, {mab, c[1], mbc, Vec3{}}, {mac, mbc, c[2], Vec3{}}, {mab, mbc, mac, Vec3{}}}};
}

void splitTreeNode(RadiosityMesh &mesh, uint32_t n) {
  if (!mesh.tree[n].isLeaf()) return;
  const MeshTreeNode parent = mesh.tree[n];
  auto corners = childCorners(parent);
  for (int k = 0; k < 4; ++k) {
    MeshTreeNode child;
    child.patch = parent.patch;
    child.vertexCount = parent.vertexCount;
    child.corners = corners[k];
    child.area = polygonArea(child.corners, child.vertexCount);
    mesh.tree[n].children[k] = static_cast<int32_t>(mesh.tree.size());
    mesh.tree.push_back(child);
  }
}

namespace {

/// The patch's shortcut grid (RadiosityMesh::TreeShortcut) for a quad tree
/// at least 3 levels deep: as many cells as about twice its nodes, at most
/// 2^7 × 2^7 and no deeper than the tree; each cell's node found by the
/// descent locateInTree makes, the cell index's bits giving each level's child.
void addTreeShortcut(RadiosityMesh &mesh, uint32_t p, size_t treeNodes, int deepest) {
  const Patch &patch = mesh.patches[p];
  if (patch.vertexCount != 4 || deepest < 3) return;
  int level = 1;
  while (level < std::min(deepest, 7) && (size_t(1) << (2 * (level + 1))) <= 2 * treeNodes) ++level;
  if (level < 3) return;
  RadiosityMesh::TreeShortcut &shortcut = mesh.treeShortcutOfPatch[p];
  shortcut.first = static_cast<uint32_t>(mesh.treeShortcutNodes.size());
  shortcut.level = level;
  const int cells = 1 << level;
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      int32_t node = patch.treeRoot, depth = 0;
      for (int bit = level - 1; bit >= 0 && !mesh.tree[size_t(node)].isLeaf(); --bit, ++depth) {
        const int ci = (i >> bit) & 1, cj = (j >> bit) & 1;
        node = mesh.tree[size_t(node)].children[cj == 0 ? ci : 3 - ci];  // (0,0), (1,0), (1,1), (0,1)
      }
      mesh.treeShortcutNodes.push_back({node, depth});
    }
}

}  // namespace

void rebuildElementsFromTrees(RadiosityMesh &mesh) {
  const ScopedTiming timing("meshing: elements of the trees");
  mesh.elements.clear();
  mesh.nodes.clear();
  mesh.nodePatch.clear();
  mesh.tVertices.clear();
  mesh.treeShortcutOfPatch.assign(mesh.patches.size(), {});
  mesh.treeShortcutNodes.clear();
  for (MeshTreeNode &t : mesh.tree) t.element = -1;
  for (uint32_t p = 0; p < mesh.patches.size(); ++p) {
    Patch &patch = mesh.patches[p];
    patch.firstElement = static_cast<uint32_t>(mesh.elements.size());
    patch.firstNode = static_cast<uint32_t>(mesh.nodes.size());
    std::map<PositionKey, uint32_t> nodeAt;
    auto nodeIndex = [&](const Vec3 &position) {
      auto [it, inserted] = nodeAt.try_emplace(keyOf(position), static_cast<uint32_t>(mesh.nodes.size()));
      if (inserted) {
        mesh.nodes.push_back(position);
        mesh.nodePatch.push_back(p);
      }
      return it->second;
    };
    // Leaves in depth-first order, so a patch's elements are contiguous.
    std::vector<std::pair<uint32_t, int>> stack{{static_cast<uint32_t>(patch.treeRoot), 0}};
    std::vector<std::pair<uint32_t, int>> leaves;  // node, depth
    size_t treeNodes = 0;
    int deepest = 0;
    while (!stack.empty()) {
      auto [n, depth] = stack.back();
      stack.pop_back();
      ++treeNodes, deepest = std::max(deepest, depth);
      const MeshTreeNode &node = mesh.tree[n];
      if (node.isLeaf()) {
        leaves.push_back({n, depth});
        continue;
      }
      for (int c = 3; c >= 0; --c) stack.push_back({static_cast<uint32_t>(node.children[c]), depth + 1});
    }
    for (auto [n, depth] : leaves) {
      MeshTreeNode &node = mesh.tree[n];
      Element e;
      e.patch = p;
      e.vertexCount = node.vertexCount;
      Vec3 centre;
      for (int k = 0; k < node.vertexCount; ++k) {
        e.nodes[k] = nodeIndex(node.corners[k]);
        centre += node.corners[k];
      }
      e.centre = centre / node.vertexCount;
      e.area = node.area;
      node.element = static_cast<int32_t>(mesh.elements.size());
      mesh.elements.push_back(e);
    }
    // T-vertices: a node at the midpoint of a leaf's edge belongs to finer
    // neighbours only; coarse leaves first, so an edge's ends are final before
    // its midpoint is set from them.
    std::stable_sort(leaves.begin(), leaves.end(), [](auto a, auto b) { return a.second < b.second; });
    std::function<void(const Vec3 &, const Vec3 &)> splitEdge = [&](const Vec3 &a, const Vec3 &b) {
      Vec3 m = (a + b) * 0.5;
      auto it = nodeAt.find(keyOf(m));
      if (it == nodeAt.end()) return;
      mesh.tVertices.push_back({it->second, nodeAt.at(keyOf(a)), nodeAt.at(keyOf(b)), 0.5f});
      splitEdge(a, m);
      splitEdge(m, b);
    };
    for (auto [n, depth] : leaves) {
      const MeshTreeNode &node = mesh.tree[n];
      for (int k = 0; k < node.vertexCount; ++k) splitEdge(node.corners[k], node.corners[(k + 1) % node.vertexCount]);
    }
    patch.elementCount = static_cast<uint32_t>(mesh.elements.size()) - patch.firstElement;
    patch.nodeCount = static_cast<uint32_t>(mesh.nodes.size()) - patch.firstNode;
    addTreeShortcut(mesh, p, treeNodes, deepest);
  }
  mesh.markNodesOnCuts();
  mesh.interpolateNodeShadingNormals();
  mesh.addCrossPatchTVertices();
  mesh.treeDescent.resize(mesh.tree.size());
  for (size_t n = 0; n < mesh.tree.size(); ++n) {
    const MeshTreeNode &t = mesh.tree[n];
    mesh.treeDescent[n] = t.isLeaf() ? std::array<int32_t, 4>{-1, t.element, -1, -1} : t.children;
  }
}

void makePatchTrees(RadiosityMesh &mesh) {
  mesh.tree.clear();
  mesh.treeDescent.clear();
  mesh.treeShortcutOfPatch.clear();
  mesh.treeShortcutNodes.clear();
  for (uint32_t p = 0; p < mesh.patches.size(); ++p) {
    Patch &patch = mesh.patches[p];
    MeshTreeNode root;
    root.patch = p;
    root.vertexCount = patch.vertexCount;
    root.corners = patch.corners;
    root.area = patch.area;
    patch.treeRoot = static_cast<int32_t>(mesh.tree.size());
    patch.divisionsU = patch.divisionsV = 1;
    mesh.tree.push_back(root);
  }
}

RadiosityMesh buildTreeMesh(const Scene &scene, const MeshOptions &options, bool buildElements) {
  // The uniform mesh's patches (and its size checks), then trees split
  // until every leaf's longest edge is at most the element size.
  MeshOptions patchesOnly = options;
  patchesOnly.crossPatchTVertices = false;  // the elements are rebuilt from the trees
  RadiosityMesh mesh = buildMesh(scene, patchesOnly);
  double edge = 0;
  for (const Element &e : mesh.elements) {
    std::vector<Vec3> poly = mesh.polygon(static_cast<uint32_t>(&e - mesh.elements.data()));
    for (size_t k = 0; k < poly.size(); ++k) edge = std::max(edge, length(poly[(k + 1) % poly.size()] - poly[k]));
  }
  makePatchTrees(mesh);
  size_t leaves = mesh.patches.size();
  for (size_t n = 0; n < mesh.tree.size(); ++n) {  // grows while we split
    const MeshTreeNode &node = mesh.tree[n];
    double longest = 0;
    for (int k = 0; k < node.vertexCount; ++k)
      longest = std::max(longest, length(node.corners[(k + 1) % node.vertexCount] - node.corners[k]));
    if (longest <= edge * (1 + 1e-9)) continue;
    if (leaves + 3 > options.maxElements)
      throw InputError(InputLocation::ofParameter("mesh-size"),
                       fmt::format("the mesh would have more than {} elements; choose a larger mesh-size or raise "
                                   "max-elements",
                                   options.maxElements));
    splitTreeNode(mesh, static_cast<uint32_t>(n));
    leaves += 3;
  }
  if (buildElements) rebuildElementsFromTrees(mesh);
  return mesh;
}

size_t refineMesh(RadiosityMesh &mesh, const std::vector<double> &errorEstimate, double threshold, size_t maxElements) {
  // The worst elements first, while the bound allows.
  std::vector<uint32_t> candidates;
  for (uint32_t e = 0; e < mesh.elements.size(); ++e)
    if (errorEstimate[e] > threshold) candidates.push_back(e);
  std::stable_sort(candidates.begin(), candidates.end(),
                   [&](uint32_t a, uint32_t b) { return errorEstimate[a] > errorEstimate[b]; });
  std::vector<int32_t> leafOf(mesh.elements.size(), -1);
  for (uint32_t n = 0; n < mesh.tree.size(); ++n)
    if (mesh.tree[n].isLeaf() && mesh.tree[n].element >= 0) leafOf[mesh.tree[n].element] = static_cast<int32_t>(n);
  size_t elements = mesh.elements.size(), split = 0;
  for (uint32_t e : candidates) {
    if (elements + 3 > maxElements) break;
    if (leafOf[e] < 0) continue;
    splitTreeNode(mesh, static_cast<uint32_t>(leafOf[e]));
    elements += 3;
    ++split;
  }
  if (split > 0) rebuildElementsFromTrees(mesh);
  return split;
}

}  // namespace radiant
