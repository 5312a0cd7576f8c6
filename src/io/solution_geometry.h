// What a version-7 solution file (docs/solution-format.md) derives on loading
// instead of storing: the mesh's geometry from each patch's face, divisions
// and tree, each face's patches, and ρ and E from the materials. The writer
// derives the same and compares bit for bit; where anything differs it
// stores that part instead, so a file always reloads to exactly the mesh it
// was written from.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "mesh/mesh.h"
#include "scene/scene.h"

namespace radiant {

/// A patch as version 7 stores it; the rest of Patch is derived.
struct CompactPatch {
  uint32_t face = 0;
  int vertexCount = 3;
  /// A piece of a cut face: its corners are in the file. Otherwise they are the
  /// face's own vertices and its area the face's (Scene::faceArea).
  bool cornersStored = false;
  std::array<Vec3, 4> corners{};  ///< when cornersStored
  int32_t divisionsU = 1, divisionsV = 1, treeRoot = -1;
};

/// The mesh's patches, elements, nodes, node patches and tree geometry
/// (element, patch, vertex count, corners, area) from compact patches and
/// each tree node's first child (−1 for a leaf; the four children are
/// consecutive), computed with the arithmetic of buildMesh (uniform lattices),
/// makePatchTrees, splitTreeNode and rebuildElementsFromTrees (trees), so
/// that it is bit for bit what they made. The element and node counts must
/// come out as `elements` and `nodes`. Returns "" or what is inconsistent
/// (the reader's error message); checks everything before it indexes or
/// allocates by it.
std::string deriveMeshGeometry(const Scene &scene, const std::vector<CompactPatch> &patches,
                               const std::vector<int32_t> &firstChild, size_t elements, size_t nodes,
                               RadiosityMesh &mesh);

/// The compact form of a mesh's patches: corners stored only where they are
/// not the face's own vertices (pieces of cut faces). Empty when some patch's
/// face is not in the scene.
std::vector<CompactPatch> compactPatches(const Scene &scene, const RadiosityMesh &mesh);

/// Whether two meshes have the same patches, elements, nodes, node patches and
/// trees, bit for bit (what deriveMeshGeometry fills).
bool sameMeshGeometry(const RadiosityMesh &a, const RadiosityMesh &b);

/// patchOfFace (each face's first patch, −1 for none) and facePatchCount
/// (how many patches it has) from the patches' faces.
void deriveFacePatches(size_t faceCount, const std::vector<Patch> &patches, std::vector<int32_t> &patchOfFace,
                       std::vector<uint32_t> &facePatchCount);

/// ρ and E per element, as initialSolution sets them from the materials (an
/// RGB scene's; a spectral pass's bands are not the scene's).
void deriveMaterialValues(const Scene &scene, const RadiosityMesh &mesh, std::vector<Bands> &reflectance,
                          std::vector<Bands> &emission);

/// Bit for bit, so that −0 and 0 (or two NaNs) are told apart as a reload would.
bool sameBits(const std::vector<Bands> &a, const std::vector<Bands> &b);

}  // namespace radiant
