// A bounding-volume tree over the scene's faces, for the queries a ray
// cannot answer: every face that may lie inside a region. Exact visibility
// (radiosity/backprojection.h) asks for the faces inside a shaft, the convex
// hull of a point and a polygon (Haines & Wallace 1991, "Shaft culling for
// efficient ray-traced radiosity"); the mesher asks for the faces whose
// boxes overlap a face's, to find where surfaces cut each other.
//
// Built once per scene, read-only afterwards, so many threads may query it.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "scene/scene.h"

namespace radiant {

struct Box3 {
  Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  void extend(const Vec3 &p) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  void extend(const Box3 &b) {
    extend(b.lo);
    extend(b.hi);
  }
  bool overlaps(const Box3 &b, double margin = 0) const {
    for (int k = 0; k < 3; ++k)
      if (lo[k] > b.hi[k] + margin || b.lo[k] > hi[k] + margin) return false;
    return true;
  }
};

/// A half-space dot(normal, p) + offset ≥ 0 (the inside).
struct HalfSpace {
  Vec3 normal;
  double offset = 0;
  double signedDistance(const Vec3 &p) const { return dot(normal, p) + offset; }
  /// True when the whole box is strictly outside (every corner at distance < −margin).
  bool excludes(const Box3 &b, double margin) const {
    Vec3 far{normal.x >= 0 ? b.hi.x : b.lo.x, normal.y >= 0 ? b.hi.y : b.lo.y, normal.z >= 0 ? b.hi.z : b.lo.z};
    return signedDistance(far) < -margin;
  }
};

class FaceTree {
 public:
  /// Holds every face but the backs of two-sided surfaces (Face::back): a
  /// query lists a pair's front for both sides, Scene::geometricFace.
  explicit FaceTree(const Scene &scene);

  /// Faces whose bounding box is not excluded by any of the half-spaces (a
  /// convex region, conservatively: a face listed may still miss it), in
  /// increasing index order. `margin` widens every half-space, metres. With
  /// more than `limit` such faces it stops early: `out` then holds limit + 1
  /// of them, in no particular order (a caller that gives up past a count
  /// need not walk a shaft full of a tessellated model).
  void facesInConvexRegion(const HalfSpace *halfSpaces, int count, double margin, std::vector<uint32_t> &out,
                           size_t limit = SIZE_MAX) const;
  /// Faces whose bounding box overlaps `box` widened by `margin`, in increasing index order.
  void facesOverlapping(const Box3 &box, double margin, std::vector<uint32_t> &out) const;

  const Box3 &faceBounds(uint32_t face) const { return faceBounds_[face]; }
  const Box3 &sceneBounds() const { return nodes_.empty() ? empty_ : nodes_[0].bounds; }

 private:
  struct Node {
    Box3 bounds;
    uint32_t first = 0, count = 0;  ///< leaf: faces_[first, first + count)
    int32_t left = -1, right = -1;  ///< inner node: children
  };
  template <typename Reject>
  void collect(const Reject &reject, std::vector<uint32_t> &out, size_t limit = SIZE_MAX) const;
  int32_t build(uint32_t first, uint32_t count, const std::vector<Vec3> &centres);

  std::vector<Box3> faceBounds_;
  std::vector<uint32_t> faces_;  ///< face indices, grouped by leaf
  std::vector<Node> nodes_;
  Box3 empty_;
};

}  // namespace radiant
