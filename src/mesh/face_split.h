// Meshing that respects the geometry: every face cut where other surfaces
// meet it, and the parts hidden inside or under other geometry left out.
//
// A radiosity element is one value of radiosity. An element that straddles
// the line where a wall stands on a floor averages the two sides: light
// leaks under the wall into the next room, and the part of the floor
// hidden under a box darkens (and, counted as a source, dims) the floor
// around it, since what it would reflect is hidden twice, once by its own
// darkness and once by the box's shadow on the links from it. So before
// meshing, each face is cut along
//   - the segments where another face crosses or touches its plane inside it
//     (a divider through a floor, a box's side standing on it), and
//   - the outlines of faces lying on it, within a small gap, parallel (a
//     light fitted just below a ceiling, a rug on a floor),
// into convex pieces (each cut's line splits the pieces it passes through),
// and a piece is hidden when, from several points of it, almost every
// direction of its front hemisphere meets the back of a face: the inside of a
// closed object, the back of a panel lying on it. Hidden pieces become no patch. The mesher keeps the
// nodes on a cut apart (RadiosityMesh::nodeOnCut): radiosity is never
// interpolated across the foot of a wall.
#pragma once

#include <cstdint>
#include <vector>

#include "raytrace/ray_tracer.h"
#include "scene/scene.h"

namespace radiant {

struct CutSegment {
  Vec3 a, b;  ///< in the face's plane, metres
};

struct FaceSplit {
  /// The visible convex pieces, each counter-clockwise seen from the face's
  /// front; empty when the face is not split (then it is meshed whole).
  std::vector<std::vector<Vec3>> pieces;
  std::vector<CutSegment> cuts;  ///< where other surfaces meet the face inside it
  size_t hiddenPieces = 0;
  bool split() const { return !pieces.empty() || hiddenPieces > 0; }
};

struct FaceSplitOptions {
  /// A face lying within this distance of another's plane, parallel and
  /// overlapping it, cuts it along its outline; relative to the scene's extent.
  double coplanarGap = 1e-2;
  /// …when its area is at least this fraction of the face's: smaller ones
  /// (the facets of a tessellated model resting on a floor) hide too little
  /// of it to be worth the slivers their outlines' lines cut it into.
  double smallestLyingFraction = 1e-4;
  /// A piece is hidden when, from its centre and from points towards each of
  /// its corners, at least this (cosine-weighted) fraction of rays meets the
  /// back of a face.
  double hiddenFraction = 0.9;
  int hiddenRays = 64;  ///< per piece, stratified over the cosine-weighted hemisphere
};

/// One entry per scene face.
std::vector<FaceSplit> splitFaces(const Scene &scene, const RayTracer &tracer, const FaceSplitOptions &options = {});

/// A convex polygon's pieces of at most four vertices (the quads and
/// triangles the mesher subdivides): triangles are cut off by the shortest
/// diagonal until four vertices remain.
std::vector<std::vector<Vec3>> convexToPatches(const std::vector<Vec3> &polygon);

}  // namespace radiant
