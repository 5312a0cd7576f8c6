// A patch's uniform lattice of elements and nodes: divisionsU × divisionsV
// quads, or divisionsU² triangles in rows (the order locate() assumes).
// buildMesh makes it, and the solution file's reader derives it again
// (io/solution_geometry.cpp): one arithmetic, so the two agree bit for bit.
#pragma once

#include <cstdint>

#include "mesh/mesh.h"

namespace radiant {

/// Appends the lattice's nodes and elements to `mesh`; `patch.firstNode`
/// must be mesh.nodes.size(), and its elements are given patch `patchIndex`.
void appendPatchLattice(const Patch &patch, uint32_t patchIndex, RadiosityMesh &mesh);

}  // namespace radiant
