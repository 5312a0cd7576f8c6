// A mesh that follows the direct light: patch trees refined until the exact
// direct irradiance (radiosity/backprojection.h) interpolates bilinearly
// within a tolerance, so shadows and their penumbrae are in the mesh.
//
// This is a-posteriori refinement by the light itself rather than by its
// predicted discontinuities (discontinuity meshing: Heckbert 1992;
// Lischinski, Tampieri & Greenberg 1992): every leaf is tested at the points
// its children would add (edge midpoints and centre) against the bilinear
// interpolation of its corners, and split where they disagree by more than
// the tolerance, down to a smallest size. Because the values are exact, the
// test is not fooled by noise, and a leaf that passes is known to
// interpolate the light to within the tolerance at those points.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "mesh/mesh.h"
#include "radiosity/backprojection.h"

namespace radiant {

/// Exact direct irradiance at points of a tree mesh, keyed by patch and exact
/// position (corners computed as midpoints by the same arithmetic have
/// the same bits, as in mesh/tree_mesh.cpp).
class DirectLightField {
 public:
  DirectLightField(const Scene &scene, const DirectIrradiance &direct) : scene_(scene), direct_(direct) {}

  /// Evaluates the points not known yet, in parallel (`threads`: 0 = all cores).
  void evaluate(const RadiosityMesh &mesh, const std::vector<std::pair<uint32_t, Vec3>> &points, int threads);
  /// The irradiance at a point evaluated before (patch, position), W·m⁻².
  const Bands &at(uint32_t patch, const Vec3 &position) const;
  bool has(uint32_t patch, const Vec3 &position) const;
  size_t size() const { return values_.size(); }

  /// The points a tree node's test needs: its corners and the corners its
  /// children would add (edge midpoints, and for a quad its centre); only
  /// its corners when `cornersOnly`.
  static void testPoints(const MeshTreeNode &node, std::vector<Vec3> &out, bool cornersOnly = false);
  /// Nodes whose longest edge is below twice this (metres) are never split,
  /// so they need the light at their corners only, and their mean is the
  /// corners' (the bilinear or linear interpolation's mean). On a tessellated
  /// model of 10⁵ small triangles this is a third of the evaluations.
  void setSmallestSplit(double minimumEdge) { smallestSplit_ = minimumEdge; }
  bool cornersOnly(const MeshTreeNode &node) const;
  /// testPoints as this field needs them (corners only where cornersOnly).
  void testPointsOf(const MeshTreeNode &node, std::vector<Vec3> &out) const {
    testPoints(node, out, cornersOnly(node));
  }
  /// Mean of the direct irradiance over a tree node: Simpson's rule on a quad
  /// (corners ¹⁄₃₆, edge midpoints ⁴⁄₃₆, centre ¹⁶⁄₃₆), the edge-midpoint rule
  /// on a triangle (exact for quadratics), the corners' mean where
  /// cornersOnly. Its test points must be evaluated.
  Bands nodeAverage(const MeshTreeNode &node) const;
  /// Largest error of the bilinear interpolation of the corners at the
  /// node's other test points, as reflected radiosity ρ·|ΔH| (W·m⁻², max band).
  double interpolationError(const MeshTreeNode &node, const Bands &reflectance) const;

 private:
  struct Key {
    uint32_t patch;
    uint64_t x, y, z;
    bool operator==(const Key &o) const { return patch == o.patch && x == o.x && y == o.y && z == o.z; }
  };
  struct KeyHash {
    size_t operator()(const Key &k) const;
  };
  static Key keyOf(uint32_t patch, const Vec3 &p);

  const Scene &scene_;
  const DirectIrradiance &direct_;
  double smallestSplit_ = 0;
  std::unordered_map<Key, Bands, KeyHash> values_;
};

struct DirectRefinementOptions {
  double minimumEdge = 0;  ///< metres: leaves whose longest edge is below twice this are not split
  double tolerance = 0;    ///< W·m⁻²: the largest interpolation error ρ·|ΔH| a leaf may keep
  size_t maxElements = 2'000'000;
  int threads = 0;
};

/// What a patch's direct-light error weighs in the refinement: its diffuse
/// reflectance ρ, or its transmittance τ where larger (a translucent face
/// passes τ of its direct light to its other side); 0 for a material that
/// reflects nothing diffusely.
std::vector<Bands> directRefinementWeights(const Scene &scene, const RadiosityMesh &mesh);

/// The area mean of ρ·H_direct (max band, W·m⁻²) over the trees' leaves, the
/// scale the refinement's tolerances are relative to. Evaluates the leaves'
/// test points into `field`. With `weightedOnly`, over the leaves of
/// patches of non-zero weight only (and only their points are evaluated).
double meanFirstBounce(const RadiosityMesh &mesh, DirectLightField &field, const std::vector<Bands> &weights,
                       int threads, bool weightedOnly = false);

/// Splits the leaves of `mesh`'s trees (buildTreeMesh) until each passes the
/// interpolation test, and fills `field` with every point tested. Patches
/// that reflect nothing (ρ = 0) are not refined. Rebuilds the elements.
/// Returns the number of leaves split.
size_t refineForDirectLight(RadiosityMesh &mesh, const std::vector<Bands> &patchReflectance, DirectLightField &field,
                            const DirectRefinementOptions &options);

}  // namespace radiant
