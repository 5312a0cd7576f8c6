// Diffuse transmission through translucent faces (Material::transmittance,
// MGF `td`): of the irradiance H arriving on one side of a face, τ leaves the
// other side diffusely. A translucent material is two-sided (Face::twin), so
// each side is a patch of its own, and the radiosity equation of a point x
// of one side reads
//   B(x) = E(x) + ρ H(x) + τ H'(x),
// H' the irradiance on the other side at the same point, τ the material's of
// the side the light leaves from. Every solver adds the last term; the two
// sides' meshes may differ (each is refined to its own light), so the
// coupling keeps the power τ H' A rather than a point value where they do.
#pragma once

#include <cstdint>
#include <vector>

#include "radiosity/solution.h"
#include "scene/scene.h"

namespace radiant {

/// τ of every element's material (0 for opaque ones and for mirrors and glass).
std::vector<Bands> elementTransmittance(const Scene &scene, const RadiosityMesh &mesh);

/// The coupling over a solution's elements (the solvers on a fixed mesh:
/// gauss-seidel, progressive, stochastic): element `to` gains τ_to Σ w H_from
/// over the elements `from` of the other side under it, w the share of its
/// area over each (from 4 × 4 points spread over it). The uniform mesher
/// meshes the two sides alike, so there each element has one `from`, w = 1;
/// where they differ (adaptive rounds, a cut on one side only) the light
/// through still lands where it belongs.
class ElementTransmission {
 public:
  ElementTransmission(const Scene &scene, const Solution &solution);
  bool empty() const { return outgoing_.empty(); }
  /// Calls f(to, gain) for every element `to` that `from`'s irradiance h
  /// passes through to, gain = τ_to · w · h (radiosity, W·m⁻²).
  template <typename F>
  void pass(size_t from, const Bands &h, F &&f) const {
    if (outgoing_.empty()) return;
    for (const auto &[to, weight] : outgoing_[from]) f(to, transmittance_[to] * h * weight);
  }
  /// For each receiving element, the elements passing light to it, with their weights.
  std::vector<std::vector<std::pair<uint32_t, double>>> incoming() const;

 private:
  std::vector<std::vector<std::pair<uint32_t, double>>>
      outgoing_;  ///< per element: (to, w); empty: nothing translucent
  std::vector<Bands> transmittance_;
};

/// The patch of the other side of `patch`'s face at the patch's centre, −1
/// when the face is one-sided or the other side has no patch there.
int32_t oppositePatch(const Scene &scene, const RadiosityMesh &mesh, uint32_t patch);

/// In a subdivision tree (nodes with `children`, `corners`, `vertexCount`,
/// `area`), from `root`, the node over the same region as a node of area
/// `area` at `point`: the two sides of a face are subdivided alike where they
/// are subdivided at all (quads at their midpoints, triangles into four), so
/// it is the node of that area containing the point, or the leaf containing
/// it where the tree is coarser. `normal` is the tree's plane's. Nodes from
/// `limit` on (made by a split since some values were kept) are taken as absent.
template <typename Node>
uint32_t coveringNode(const std::vector<Node> &nodes, uint32_t root, const Vec3 &point, const Vec3 &normal, double area,
                      size_t limit = SIZE_MAX) {
  uint32_t n = root;
  while (nodes[n].children[0] >= 0 && size_t(nodes[n].children[0]) < limit && nodes[n].area > area * (1 + 1e-6)) {
    // The child the point lies deepest inside (round-off on shared edges).
    uint32_t best = uint32_t(nodes[n].children[0]);
    double bestDepth = -INFINITY;
    for (int c = 0; c < 4; ++c) {
      const Node &child = nodes[size_t(nodes[n].children[c])];
      double depth = INFINITY;
      for (int k = 0; k < child.vertexCount; ++k) {
        const Vec3 &a = child.corners[k], &b = child.corners[(k + 1) % child.vertexCount];
        const Vec3 inward = cross(normal, b - a);
        const double l = length(inward);
        if (l > 0) depth = std::min(depth, dot(point - a, inward) / l);
      }
      if (depth > bestDepth) bestDepth = depth, best = uint32_t(nodes[n].children[c]);
    }
    n = best;
  }
  return n;
}

}  // namespace radiant
