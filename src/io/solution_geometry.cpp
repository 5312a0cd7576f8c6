#include "io/solution_geometry.h"

#include <fmt/format.h>

#include <bit>
#include <cstring>
#include <map>
#include <tuple>

#include "mesh/patch_lattice.h"
#include "raytrace/surface_detail.h"

namespace radiant {

namespace {

bool identicalBits(double a, double b) {
  return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b);
}
bool identicalBits(const Vec3 &a, const Vec3 &b) {
  return identicalBits(a.x, b.x) && identicalBits(a.y, b.y) && identicalBits(a.z, b.z);
}
template <size_t N>
bool identicalBits(const std::array<Vec3, N> &a, const std::array<Vec3, N> &b) {
  for (size_t k = 0; k < N; ++k)
    if (!identicalBits(a[k], b[k])) return false;
  return true;
}

// (Names of their own: a unity build puts mesh.cpp and tree_mesh.cpp, whose
// helpers these mirror, into one translation unit with this file.)
// The arithmetic below is the mesh builders' (src/mesh/mesh.cpp, tree_mesh.cpp),
// expression for expression: the writer checks the result bit for bit and
// stores the geometry whenever it differs, so a change there costs file size,
// never correctness.

/// buildMesh's patch area and splitTreeNode's node area.
double areaOfPolygon(const std::array<Vec3, 4> &c, int count) {
  double area = 0;
  for (int k = 1; k + 1 < count; ++k) area += 0.5 * length(cross(c[k] - c[0], c[k + 1] - c[0]));
  return area;
}

/// rebuildElementsFromTrees' key: equal corners have equal bits.
struct CornerBits {
  uint64_t x, y, z;
  bool operator<(const CornerBits &o) const { return std::tie(x, y, z) < std::tie(o.x, o.y, o.z); }
};
CornerBits cornerBitsOf(const Vec3 &p) {
  return {std::bit_cast<uint64_t>(p.x), std::bit_cast<uint64_t>(p.y), std::bit_cast<uint64_t>(p.z)};
}

}  // namespace

std::string deriveMeshGeometry(const Scene &scene, const std::vector<CompactPatch> &patches,
                               const std::vector<int32_t> &firstChild, size_t elements, size_t nodes,
                               RadiosityMesh &mesh) {
  const size_t treeNodes = firstChild.size();
  mesh.patches.assign(patches.size(), Patch{});
  mesh.tree.assign(treeNodes, MeshTreeNode{});
  mesh.elements.clear();
  mesh.nodes.clear();
  mesh.nodePatch.clear();
  // Patches: the face's material, object and normal; its vertices and area unless stored.
  for (size_t p = 0; p < patches.size(); ++p) {
    const CompactPatch &c = patches[p];
    Patch &patch = mesh.patches[p];
    if (c.face >= scene.faces.size()) return "a patch refers to a face that does not exist";
    const Face &face = scene.faces[c.face];
    if (c.vertexCount < 3 || c.vertexCount > 4 || c.divisionsU < 1 || c.divisionsV < 1 || c.treeRoot < -1 ||
        (c.treeRoot >= 0 && size_t(c.treeRoot) >= treeNodes) || (!c.cornersStored && face.vertexCount != c.vertexCount))
      return "a patch's subdivision is inconsistent";
    patch.face = c.face;
    patch.material = face.material;
    patch.object = face.object;
    patch.vertexCount = c.vertexCount;
    patch.divisionsU = c.divisionsU;
    patch.divisionsV = c.divisionsV;
    patch.treeRoot = c.treeRoot;
    patch.normal = scene.faceNormal(face);
    if (c.cornersStored) {
      for (int k = 0; k < c.vertexCount; ++k) patch.corners[k] = c.corners[k];
      patch.area = areaOfPolygon(patch.corners, patch.vertexCount);
    } else {
      for (int k = 0; k < c.vertexCount; ++k) patch.corners[k] = scene.positions[face.vertices[k]];
      patch.area = scene.faceArea(face);
    }
  }
  // Trees: each root is one patch's, every other node one node's child, and
  // children come after their parent (so this one pass sees parents first).
  std::vector<uint8_t> owned(treeNodes, 0);
  std::vector<int> depth(treeNodes, 0);
  for (uint32_t p = 0; p < patches.size(); ++p) {
    const int32_t root = mesh.patches[p].treeRoot;
    if (root < 0) continue;
    if (owned[size_t(root)]) return "the subdivision tree is inconsistent";
    owned[size_t(root)] = 1;
    MeshTreeNode &node = mesh.tree[size_t(root)];
    node.patch = p;
    node.vertexCount = mesh.patches[p].vertexCount;
    node.corners = mesh.patches[p].corners;
    node.area = mesh.patches[p].area;
  }
  for (size_t n = 0; n < treeNodes; ++n) {
    if (!owned[n]) return "the subdivision tree is inconsistent";
    const int32_t first = firstChild[n];
    if (first < 0) continue;
    if (size_t(first) <= n || size_t(first) + 3 >= treeNodes) return "the subdivision tree is inconsistent";
    if (depth[n] + 1 > kMaxSolutionTreeDepth)
      return fmt::format("a patch's subdivision tree is deeper than {} levels", kMaxSolutionTreeDepth);
    const std::array<std::array<Vec3, 4>, 4> corners = childCorners(mesh.tree[n]);
    for (int k = 0; k < 4; ++k) {
      const size_t c = size_t(first) + size_t(k);
      if (owned[c]) return "the subdivision tree is inconsistent";
      owned[c] = 1;
      depth[c] = depth[n] + 1;
      MeshTreeNode &child = mesh.tree[c];
      mesh.tree[n].children[k] = int32_t(c);
      child.patch = mesh.tree[n].patch;
      child.vertexCount = mesh.tree[n].vertexCount;
      child.corners = corners[k];
      child.area = areaOfPolygon(child.corners, child.vertexCount);
    }
  }
  // Elements and nodes, patch by patch.
  const char *tooMany = "the patches make more elements or nodes than the file counts";
  for (uint32_t p = 0; p < patches.size(); ++p) {
    Patch &patch = mesh.patches[p];
    patch.firstElement = uint32_t(mesh.elements.size());
    patch.firstNode = uint32_t(mesh.nodes.size());
    if (patch.treeRoot < 0) {
      // buildMesh's lattice; its size is checked first, in 64 bits.
      const uint64_t nU = uint64_t(patch.divisionsU), nV = uint64_t(patch.divisionsV);
      if (nU > elements || nV > elements) return tooMany;
      const uint64_t count = patch.vertexCount == 4 ? nU * nV : nU * nU;
      const uint64_t corners = patch.vertexCount == 4 ? (nU + 1) * (nV + 1) : (nU + 1) * (nU + 2) / 2;
      if (count > elements - mesh.elements.size() || corners > nodes - mesh.nodes.size()) return tooMany;
      appendPatchLattice(patch, p, mesh);
    } else {
      // rebuildElementsFromTrees: leaves depth first, children 0 to 3; a node per distinct corner.
      std::map<CornerBits, uint32_t> nodeAt;
      std::vector<uint32_t> stack{uint32_t(patch.treeRoot)};
      while (!stack.empty()) {
        const uint32_t n = stack.back();
        stack.pop_back();
        MeshTreeNode &leaf = mesh.tree[n];
        if (!leaf.isLeaf()) {
          for (int c = 3; c >= 0; --c) stack.push_back(uint32_t(leaf.children[c]));
          continue;
        }
        if (mesh.elements.size() >= elements) return tooMany;
        Element e;
        e.patch = p;
        e.vertexCount = leaf.vertexCount;
        Vec3 centre;
        for (int k = 0; k < leaf.vertexCount; ++k) {
          auto [it, inserted] = nodeAt.try_emplace(cornerBitsOf(leaf.corners[k]), uint32_t(mesh.nodes.size()));
          if (inserted) {
            if (mesh.nodes.size() >= nodes) return tooMany;
            mesh.nodes.push_back(leaf.corners[k]);
          }
          e.nodes[k] = it->second;
          centre += leaf.corners[k];
        }
        e.centre = centre / leaf.vertexCount;
        e.area = leaf.area;
        leaf.element = int32_t(mesh.elements.size());
        mesh.elements.push_back(e);
      }
    }
    patch.elementCount = uint32_t(mesh.elements.size()) - patch.firstElement;
    patch.nodeCount = uint32_t(mesh.nodes.size()) - patch.firstNode;
    mesh.nodePatch.resize(mesh.nodes.size(), p);
  }
  if (mesh.elements.size() != elements || mesh.nodes.size() != nodes)
    return "the patches make fewer elements or nodes than the file counts";
  return "";
}

std::vector<CompactPatch> compactPatches(const Scene &scene, const RadiosityMesh &mesh) {
  std::vector<CompactPatch> out(mesh.patches.size());
  for (size_t p = 0; p < mesh.patches.size(); ++p) {
    const Patch &patch = mesh.patches[p];
    if (patch.face >= scene.faces.size()) return {};
    const Face &face = scene.faces[patch.face];
    CompactPatch &c = out[p];
    c.face = patch.face;
    c.vertexCount = patch.vertexCount;
    c.divisionsU = patch.divisionsU, c.divisionsV = patch.divisionsV, c.treeRoot = patch.treeRoot;
    bool whole = face.vertexCount == patch.vertexCount && identicalBits(patch.area, scene.faceArea(face));
    for (int k = 0; k < 4 && whole; ++k)
      whole = identicalBits(patch.corners[k], k < face.vertexCount ? scene.positions[face.vertices[k]] : Vec3{});
    c.cornersStored = !whole;
    if (c.cornersStored) c.corners = patch.corners;
  }
  return out;
}

bool sameMeshGeometry(const RadiosityMesh &a, const RadiosityMesh &b) {
  if (a.patches.size() != b.patches.size() || a.elements.size() != b.elements.size() ||
      a.nodes.size() != b.nodes.size() || a.nodePatch != b.nodePatch || a.tree.size() != b.tree.size())
    return false;
  for (size_t p = 0; p < a.patches.size(); ++p) {
    const Patch &x = a.patches[p], &y = b.patches[p];
    if (x.face != y.face || x.material != y.material || x.object != y.object || x.treeRoot != y.treeRoot ||
        x.vertexCount != y.vertexCount || !identicalBits(x.corners, y.corners) || !identicalBits(x.normal, y.normal) ||
        !identicalBits(x.area, y.area) || x.divisionsU != y.divisionsU || x.divisionsV != y.divisionsV ||
        x.firstElement != y.firstElement || x.elementCount != y.elementCount || x.firstNode != y.firstNode ||
        x.nodeCount != y.nodeCount)
      return false;
  }
  for (size_t e = 0; e < a.elements.size(); ++e) {
    const Element &x = a.elements[e], &y = b.elements[e];
    if (x.patch != y.patch || x.vertexCount != y.vertexCount || x.nodes != y.nodes ||
        !identicalBits(x.centre, y.centre) || !identicalBits(x.area, y.area))
      return false;
  }
  for (size_t v = 0; v < a.nodes.size(); ++v)
    if (!identicalBits(a.nodes[v], b.nodes[v])) return false;
  for (size_t n = 0; n < a.tree.size(); ++n) {
    const MeshTreeNode &x = a.tree[n], &y = b.tree[n];
    if (x.children != y.children || x.element != y.element || x.patch != y.patch || x.vertexCount != y.vertexCount ||
        !identicalBits(x.corners, y.corners) || !identicalBits(x.area, y.area))
      return false;
  }
  return true;
}

void deriveFacePatches(size_t faceCount, const std::vector<Patch> &patches, std::vector<int32_t> &patchOfFace,
                       std::vector<uint32_t> &facePatchCount) {
  patchOfFace.assign(faceCount, -1);
  facePatchCount.assign(faceCount, 0);
  for (size_t p = 0; p < patches.size(); ++p) {
    const uint32_t f = patches[p].face;
    if (f >= faceCount) continue;
    if (patchOfFace[f] < 0) patchOfFace[f] = int32_t(p);
    ++facePatchCount[f];
  }
}

void deriveMaterialValues(const Scene &scene, const RadiosityMesh &mesh, std::vector<Bands> &reflectance,
                          std::vector<Bands> &emission) {
  // initialSolution's rule (src/radiosity/solution.cpp).
  const size_t n = mesh.elements.size();
  reflectance.resize(n);
  emission.resize(n);
  for (size_t e = 0; e < n; ++e) {
    const Patch &patch = mesh.patchOf(uint32_t(e));
    const Material &m = scene.materials[patch.material];
    reflectance[e] = m.kind == MaterialKind::Lambertian || m.kind == MaterialKind::Glossy ? m.diffuse : Bands(0.0);
    if (m.diffuseTextureIndex >= 0 && reflectance[e].max() > 0) {
      const Element &element = mesh.elements[e];
      std::array<Vec3, 4> corners;
      for (int k = 0; k < element.vertexCount; ++k) corners[k] = mesh.nodes[element.nodes[k]];
      reflectance[e] = averageDiffuse(scene, patch.face, std::span<const Vec3>(corners.data(), element.vertexCount));
    }
    emission[e] = m.emission * kPi;
  }
}

bool sameBits(const std::vector<Bands> &a, const std::vector<Bands> &b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < kBandCount; ++k)
      if (!identicalBits(a[i][k], b[i][k])) return false;
  return true;
}

}  // namespace radiant
