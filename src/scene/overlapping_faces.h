// Faces that lie in one plane, face the same way and overlap: two copies of a
// floor, a decal modelled on a wall. Each copy receives the full light that
// reaches the plane, so a radiosity solution that gives both their form
// factors counts that light twice (a closed room then absorbs more than it
// emits, and a shooting solver never converges). The loader warns about them;
// the solvers name them when their residual grows instead of falling.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace radiant {

struct FaceOverlap {
  uint32_t first = 0, second = 0;  ///< indices into Scene::faces, first < second
  double area = 0;                 ///< m², the area they share
};

/// Every pair of faces in one plane (normals within 10⁻⁶, offsets within 10⁻⁷
/// of the scene's size), facing the same way, that share more than 10⁻⁶ of the
/// smaller one's area; at most `maxPairs`, in face order. Faces that only touch
/// along an edge (a tessellated floor) do not overlap.
std::vector<FaceOverlap> findOverlappingFaces(const Scene &scene, size_t maxPairs = SIZE_MAX);

/// "3 pairs of faces overlap in one plane, facing the same way (the first: a
/// face of object 'a' and one of 'b', sharing 0.25 m²)".
std::string describeOverlappingFaces(const Scene &scene, const std::vector<FaceOverlap> &overlaps);

}  // namespace radiant
