// The radiosity mesh: input faces become patches, patches are subdivided into
// elements, and elements share nodes so radiosity interpolated at the nodes is
// continuous inside a patch (Cohen & Wallace ch. 6).
//
// Subdivision is uniform per patch, to a target edge length: a quad patch
// becomes an nU × nV grid of quads (its bilinear parameterisation cut evenly),
// a triangle patch n² triangles (the lattice that n-fold edge splitting makes;
// n = 2^k is k rounds of four-way splitting). Elements of one patch share the
// lattice's nodes, so there are no T-vertices inside a patch. Patches do not
// share nodes: radiosity may be discontinuous across a patch boundary, as it
// is at the creases of a room.
//
// Every face is one-sided here: its elements carry the radiosity leaving the
// front (counter-clockwise) side.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "mesh/face_split.h"
#include "scene/scene.h"

namespace radiant {

/// A shading normal in single precision (a model's vertex normals, OBJ `vn`,
/// glTF NORMAL): unit, or zero where there is none.
using ShadingNormal = std::array<float, 3>;

/// cos 2°: two patches' normals (or two nodes' shading normals) closer than
/// this belong to one smooth surface, whose nodes share their values.
constexpr double kSmoothSurfaceCosine = 0.99939;

inline Vec3 toVec3(const ShadingNormal &n) {
  return Vec3{n[0], n[1], n[2]};
}

/// Whether two shading normals are both present and within 2° of each other.
inline bool sameShadingNormal(const ShadingNormal &a, const ShadingNormal &b) {
  const double d = double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
  return d > kSmoothSurfaceCosine;  // false when either is zero
}

struct MeshOptions {
  /// Target element edge length, metres; 0 chooses defaultEdgeFraction of
  /// the scene's largest bounding-box side.
  double maxEdgeLength = 0;
  double defaultEdgeFraction = 1.0 / 8;
  /// Refuse meshes above this many elements (a clear error, not an allocation).
  size_t maxElements = 2'000'000;
  /// One entry per face (mesh/face_split.h): a split face becomes a patch per
  /// quad or triangle of its visible pieces, and its hidden pieces none.
  /// nullptr: every face is one patch.
  const std::vector<FaceSplit> *faceSplits = nullptr;
  /// Join the lattices of neighbouring patches by T-vertices (false where the
  /// caller rebuilds the elements anyway: buildTreeMesh).
  bool crossPatchTVertices = true;
};

/// The deepest subdivision tree a solution may hold: far more levels than any
/// refinement makes (each halves the node's edges); the solution reader refuses
/// a file with deeper trees, and the walks over trees rely on it.
constexpr int kMaxSolutionTreeDepth = 64;

/// A node of a patch's subdivision tree (hierarchical radiosity): four
/// children, or a leaf that is an element. Quads split at their bilinear
/// midpoints, triangles into four by their edge midpoints (children: the
/// corners at vertex 0, 1, 2, then the middle triangle).
struct MeshTreeNode {
  std::array<int32_t, 4> children{-1, -1, -1, -1};
  int32_t element = -1;  ///< ≥ 0 for a leaf
  uint32_t patch = 0;
  int vertexCount = 4;
  std::array<Vec3, 4> corners{};
  double area = 0;
  bool isLeaf() const { return children[0] < 0; }
  /// The longest of its edges: what the refinements compare with their smallest size.
  double longestEdge() const {
    double longest = 0;
    for (int k = 0; k < vertexCount; ++k)
      longest = std::max(longest, length(corners[(k + 1) % vertexCount] - corners[k]));
    return longest;
  }
};

struct Patch {
  uint32_t face = 0, material = 0, object = 0;
  /// ≥ 0: the patch's elements are the leaves of this subdivision tree
  /// (RadiosityMesh::tree) instead of a uniform nU × nV grid.
  int32_t treeRoot = -1;
  int vertexCount = 3;
  std::array<Vec3, 4> corners{};
  Vec3 normal;  ///< front side, unit
  double area = 0;
  int divisionsU = 1, divisionsV = 1;  ///< quads: along corner 0→1 and 0→3; triangles: n and n
  /// Unit normals of the edges, in the patch's plane, pointing inwards
  /// (set by buildPatchLookup; what patchAt measures depth with).
  std::array<Vec3, 4> inwardEdgeNormals{};
  uint32_t firstElement = 0, elementCount = 0;
  uint32_t firstNode = 0, nodeCount = 0;

  /// How far a point of the patch's plane lies inside its edges, metres
  /// (negative outside): the smallest distance to an edge's line.
  double depthInside(const Vec3 &p) const {
    double depth = INFINITY;
    for (int v = 0; v < vertexCount; ++v)
      depth = std::min(depth, dot(p - corners[size_t(v)], inwardEdgeNormals[size_t(v)]));
    return depth;
  }
};

struct Element {
  uint32_t patch = 0;
  int vertexCount = 3;
  std::array<uint32_t, 4> nodes{};  ///< counter-clockwise, into RadiosityMesh::nodes
  Vec3 centre;
  double area = 0;
};

/// A point inside an element, for interpolation: quads use bilinear (s, t) in
/// [0,1]² over nodes 0,1,2,3; triangles barycentric weights (1−s−t, s, t).
struct MeshLocation {
  uint32_t element = 0;
  double s = 0, t = 0;
};

struct RadiosityMesh {
  std::vector<Patch> patches;
  std::vector<Element> elements;
  std::vector<Vec3> nodes;           ///< positions, metres
  std::vector<uint32_t> nodePatch;   ///< the patch each node belongs to
  std::vector<int32_t> patchOfFace;  ///< Scene::faces index → its (first) patch, −1 if none
  /// Patches of each face, consecutive from patchOfFace: 1, or more for a face
  /// cut where other surfaces meet it (mesh/face_split.h). Empty: all 1.
  std::vector<uint32_t> facePatchCount;
  /// Per node: it lies on a cut of its face (where another surface meets
  /// it), so it is never pooled with a node of another patch there. Empty: none.
  std::vector<uint8_t> nodeOnCut;
  /// The cuts of each face (empty when no face is cut); what nodeOnCut is computed from.
  std::vector<std::vector<CutSegment>> faceCuts;
  std::vector<MeshTreeNode> tree;  ///< subdivision trees of hierarchical patches
  /// The trees' children alone, 16 bytes a node (a leaf: {−1, its element}),
  /// for locateInTree: descending the full nodes (about 150 bytes each) missed
  /// the cache at every level, 17 % of a stochastic solve of cornell-knots
  /// whose walls are trees. Set by rebuildElementsFromTrees; ignored once
  /// the tree has changed size since.
  std::vector<std::array<int32_t, 4>> treeDescent;
  /// Per patch (with treeDescent): a quad tree's nodes at depth `level` on
  /// a 2^level × 2^level grid of the patch's (u, v) — or the leaf above a
  /// cell where the tree is shallower — from which locateInTree descends
  /// instead of from the root: a wall refined to 1/256 of the scene is 8
  /// levels deep, a dependent load each, for every ray and pixel sample
  /// that lands on it. level 0: none (triangles, shallow trees).
  struct TreeShortcut {
    uint32_t first = 0;  ///< into treeShortcutNodes, row by row (v), u within a row
    int32_t level = 0;
  };
  std::vector<TreeShortcut> treeShortcutOfPatch;
  /// The shortcut grids' cells: {node, its depth}.
  std::vector<std::array<int32_t, 2>> treeShortcutNodes;
  /// Per patch: its face's vertex normals (Scene::normals, as the scene gives
  /// them, not flipped) interpolated at the patch's corners: the face's own
  /// for a whole face, the fan's linear interpolation (the ray tracer's) at
  /// the corners of a cut face's piece; zero for a face without them. Set by
  /// setShadingNormals; empty when no face has vertex normals.
  std::vector<std::array<ShadingNormal, 4>> patchCornerNormals;
  /// Per node: the shading normal of the surface there, unit, on its patch's
  /// front side (the ray tracer's rule: interpolated, normalised, flipped to
  /// the geometric normal's side); its patch's corner normals interpolated at
  /// the node (barycentric on triangles, bilinear on quads: along an edge
  /// both are the linear blend of its ends, as on the neighbour across it).
  /// Zero where the face has none. Nodes of two faces that share a vertex's
  /// normal get the same one, so they pool (Solution::nodePools) although the
  /// faces' own normals differ: a tessellated smooth surface is shown smooth.
  /// Empty when patchCornerNormals is.
  std::vector<ShadingNormal> nodeShadingNormals;
  /// Nodes inside a coarser neighbour's edge, in coarse-to-fine order: their
  /// value must be the edge's interpolation between its ends, (1 − t)·start +
  /// t·end, or interpolation would crack there. Within a patch's tree t is ½
  /// (an edge's midpoint); across patches (the pieces of a cut face, the
  /// faces of one smooth surface) any t in (0, 1).
  struct TVertex {
    uint32_t node, edgeStart, edgeEnd;
    float t = 0.5f;
  };
  std::vector<TVertex> tVertices;

  const Patch &patchOf(uint32_t element) const { return patches[elements[element].patch]; }
  const Vec3 &normalOf(uint32_t element) const { return patchOf(element).normal; }
  /// The element's polygon (3 or 4 vertices, counter-clockwise).
  std::vector<Vec3> polygon(uint32_t element) const;

  /// The element containing `position` on scene face `face` (which must have
  /// a patch), with local coordinates for interpolation. Points slightly
  /// outside (round-off) are clamped to the nearest element.
  MeshLocation locate(uint32_t face, const Vec3 &position) const;
  /// The patch of face `face` containing `position` (of a cut face's patches
  /// the one it lies deepest inside), or −1 when the face has none.
  int32_t patchAt(uint32_t face, const Vec3 &position) const;
  /// Recomputes nodeOnCut from faceCuts and the nodes.
  void markNodesOnCuts();
  /// The scene's vertex normals at the patches' corners (patchCornerNormals)
  /// and at the nodes (nodeShadingNormals); both empty when no face of the
  /// patches has vertex normals. buildMesh and the solution file's reader call it.
  void setShadingNormals(const Scene &scene);
  /// Recomputes nodeShadingNormals from patchCornerNormals and the nodes
  /// (rebuildElementsFromTrees calls it, before addCrossPatchTVertices).
  void interpolateNodeShadingNormals();
  /// Whether two nodes lie on one smooth surface: same material, and their
  /// patches' normals within 2° or both their shading normals within 2°.
  bool sameSmoothSurface(uint32_t nodeA, uint32_t nodeB) const;
  /// Adds the T-vertices across patches: a node of one patch strictly inside
  /// a boundary edge of an element of another patch of the same smooth
  /// surface (same material, normals within 2°, or the node's shading normal
  /// within 2° of the edge's there), not on a cut. Sorts all
  /// T-vertices coarse to fine. Called by the mesh builders.
  void addCrossPatchTVertices();
  /// Builds the lookup patchAt uses on faces with several patches (buildMesh
  /// does; call it after filling patches and facePatchCount by hand).
  void buildPatchLookup();

  /// Per face with several patches: a grid over the face's plane listing the
  /// patches whose bounds meet each cell, so patchAt tests a few, not all.
  struct PatchGrid {
    Vec3 origin, axisU, axisV;  ///< the face's plane: origin + u·axisU + v·axisV, unit axes
    double cellU = 1, cellV = 1;
    int cellsU = 1, cellsV = 1;
    std::vector<uint32_t> cellStart;  ///< cellsU·cellsV + 1 offsets into patches
    std::vector<uint32_t> patches;
  };
  std::vector<int32_t> patchGridOfFace;  ///< index into patchGrids, −1 for faces with one patch
  std::vector<PatchGrid> patchGrids;
  MeshLocation locateInTree(uint32_t patch, const Vec3 &position) const;
  /// The element a ray's hit on `face` lands in, for each face: ≥ 0 where
  /// the face is one patch meshed as one element (a model's facet), found
  /// without reading the patch; kLocateElement where locate must find it;
  /// kNoElement where the face has no patch (hidden).
  static constexpr int32_t kLocateElement = -1, kNoElement = -2;
  std::vector<int32_t> wholeFaceElements() const;
  /// Interpolation weights of the element's nodes at a location (sum to 1).
  std::array<double, 4> nodeWeights(const MeshLocation &location) const;
};

/// Throws InputError when the mesh would exceed options.maxElements.
RadiosityMesh buildMesh(const Scene &scene, const MeshOptions &options);

// Tree meshes (src/mesh/tree_mesh.cpp): every patch a subdivision tree, its
// leaves the elements, for adaptive refinement.

/// Like buildMesh, but each patch is a tree split four-way until every leaf
/// is no longer than the uniform mesh's longest element edge.
/// With `buildElements` false the trees only: the caller refines them and
/// calls rebuildElementsFromTrees once (each build of the elements and their
/// T-vertices costs a few tenths of a second on 10⁵ faces).
RadiosityMesh buildTreeMesh(const Scene &scene, const MeshOptions &options, bool buildElements = true);
/// Makes every patch the root of a one-node tree (its elements are then
/// rebuilt from the trees by rebuildElementsFromTrees).
void makePatchTrees(RadiosityMesh &mesh);
/// Splits the leaves whose element error estimate exceeds `threshold`, worst
/// first, while the element count stays within `maxElements`; rebuilds the
/// elements, nodes and T-vertices. Returns how many elements were split.
size_t refineMesh(RadiosityMesh &mesh, const std::vector<double> &errorEstimate, double threshold, size_t maxElements);
/// Splits one tree leaf into four children (elements are not rebuilt).
void splitTreeNode(RadiosityMesh &mesh, uint32_t node);
/// The four children's corners of a tree node, in locateInTree's order.
std::array<std::array<Vec3, 4>, 4> childCorners(const MeshTreeNode &node);
/// Elements from the trees' leaves (depth-first per patch), nodes shared by
/// position within a patch, T-vertices coarse to fine.
void rebuildElementsFromTrees(RadiosityMesh &mesh);

}  // namespace radiant
