// Clusters of patches: the levels above the patches' own subdivision trees,
// so that hierarchical radiosity links groups of surfaces that are far from
// each other with one link instead of linking every pair of patches
// (Smits, Arvo & Greenberg, "A clustering algorithm for radiosity in complex
// environments", SIGGRAPH 1994; Sillion, "A unified hierarchical algorithm
// for global illumination with scattering volumes and object clusters",
// IEEE TVCG 1995). Without them the first linking is P² pairs: 10¹⁰ for a
// tessellated model of 10⁵ triangles.
//
// A bounding-volume tree over the patches, built top-down: a cluster keeps
// as its own the patches too large for a child (a box extent over half the
// cluster's along some axis — walls and floors stay near the top, as
// Christensen 1995 and RenderPark do) and splits the rest at the median of
// their centres along the longest axis, until 4 or fewer are left. The
// patches of a cluster and all its descendants are consecutive in
// `order` (its own first), so "does cluster c contain patch p" is one
// comparison of positions.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "mesh/mesh.h"
#include "raytrace/face_tree.h"

namespace radiant {

struct Cluster {
  Box3 bounds;
  Vec3 centre;                    ///< area-weighted centroid of its patches
  double area = 0;                ///< one-sided area of all its patches, m²
  uint32_t first = 0, count = 0;  ///< its patches and its descendants': order[first, first + count)
  uint32_t ownCount = 0;          ///< the first ownCount of them are its own
  int32_t left = -1, right = -1;  ///< child clusters (both or neither)
  int32_t parent = -1;
  bool hasChildren() const { return left >= 0; }
};

struct ClusterTree {
  std::vector<Cluster> clusters;     ///< [0] is the root; a parent precedes its children
  std::vector<uint32_t> order;       ///< patch indices, grouped by cluster
  std::vector<uint32_t> positionOf;  ///< per patch: its index in order
  std::vector<uint32_t> ownerOf;     ///< per patch: the cluster it is an own patch of

  bool contains(uint32_t cluster, uint32_t patch) const {
    const Cluster &c = clusters[cluster];
    return positionOf[patch] - c.first < c.count;
  }
};

/// Builds the tree over the mesh's patches (none: an empty tree).
ClusterTree buildClusterTree(const RadiosityMesh &mesh);

}  // namespace radiant
