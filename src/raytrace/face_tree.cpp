#include "raytrace/face_tree.h"

#include <algorithm>
#include <numeric>

namespace radiant {

namespace {
constexpr uint32_t kLeafSize = 4;
}

FaceTree::FaceTree(const Scene &scene) {
  const uint32_t count = static_cast<uint32_t>(scene.faces.size());
  faceBounds_.resize(count);
  std::vector<Vec3> centres(count);
  for (uint32_t f = 0; f < count; ++f) {
    const Face &face = scene.faces[f];
    for (int k = 0; k < face.vertexCount; ++k) faceBounds_[f].extend(scene.positions[face.vertices[k]]);
    centres[f] = (faceBounds_[f].lo + faceBounds_[f].hi) * 0.5;
  }
  // A back face (Face::back) is the same polygon as its front: the tree holds the front only.
  for (uint32_t f = 0; f < count; ++f)
    if (!scene.faces[f].back) faces_.push_back(f);
  const uint32_t held = static_cast<uint32_t>(faces_.size());
  if (held == 0) return;
  nodes_.reserve(2 * (held / kLeafSize + 1));
  build(0, held, centres);
}

int32_t FaceTree::build(uint32_t first, uint32_t count, const std::vector<Vec3> &centres) {
  const int32_t index = static_cast<int32_t>(nodes_.size());
  nodes_.push_back({});
  Box3 bounds, centreBounds;
  for (uint32_t i = first; i < first + count; ++i) {
    bounds.extend(faceBounds_[faces_[i]]);
    centreBounds.extend(centres[faces_[i]]);
  }
  nodes_[index].bounds = bounds;
  if (count <= kLeafSize) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  // Median split along the longest axis of the centres: balanced, so the
  // depth stays logarithmic whatever the scene's distribution.
  Vec3 extent = centreBounds.hi - centreBounds.lo;
  int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const uint32_t half = count / 2;
  std::nth_element(faces_.begin() + first, faces_.begin() + first + half, faces_.begin() + first + count,
                   [&](uint32_t a, uint32_t b) { return centres[a][axis] < centres[b][axis]; });
  const int32_t left = build(first, half, centres);
  const int32_t right = build(first + half, count - half, centres);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

template <typename Reject>
void FaceTree::collect(const Reject &reject, std::vector<uint32_t> &out, size_t limit) const {
  out.clear();
  if (nodes_.empty()) return;
  int32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node &node = nodes_[stack[--top]];
    if (reject(node.bounds)) continue;
    if (node.left < 0) {
      for (uint32_t i = node.first; i < node.first + node.count; ++i)
        if (!reject(faceBounds_[faces_[i]])) out.push_back(faces_[i]);
      if (out.size() > limit) return;
      continue;
    }
    stack[top++] = node.left;
    stack[top++] = node.right;
  }
  std::sort(out.begin(), out.end());
}

void FaceTree::facesInConvexRegion(const HalfSpace *halfSpaces, int count, double margin, std::vector<uint32_t> &out,
                                   size_t limit) const {
  collect(
      [&](const Box3 &b) {
        for (int k = 0; k < count; ++k)
          if (halfSpaces[k].excludes(b, margin)) return true;
        return false;
      },
      out, limit);
}

void FaceTree::facesOverlapping(const Box3 &box, double margin, std::vector<uint32_t> &out) const {
  collect([&](const Box3 &b) { return !b.overlaps(box, margin); }, out);
}

}  // namespace radiant
