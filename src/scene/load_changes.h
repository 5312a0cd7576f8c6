// What the scene loaders dropped or changed in the input, and where: for
// `radiant info` (and any warning) to name a face a user can find, by its
// object and a position in the scene, not by a face number that no modeller
// shows.
//
// Every loader builds faces through Scene::addFace and detail::addPolygon
// (scene/load_detail.h), and those record each change here as they make it.
// A file of 10⁶ broken faces must not hold 10⁶ records: each kind keeps its
// count and only its first kListedPerKind changes.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "util/math.h"

namespace radiant {

enum class LoadChangeKind : uint8_t {
  DegenerateFace,  ///< dropped: zero area, fewer than three distinct corners, or a corner not finite
  RepeatedFace,    ///< dropped: the same corners as an earlier face, facing the same way
  CollinearQuad,   ///< a quad with three corners on one line, kept as the triangle it is
  BackToBack,      ///< two faces with the same corners in reverse order, paired as one two-sided surface
};
constexpr size_t kLoadChangeKinds = 4;

/// "degenerate face", "repeated face", "quad made a triangle", "faces paired back to back".
const char *loadChangeName(LoadChangeKind kind);
/// "dropped", "merged": what became of the input.
const char *loadChangeAction(LoadChangeKind kind);
/// A stable key for scripts: "degenerate_faces", "repeated_faces", "collinear_quads", "back_to_back_pairs".
const char *loadChangeKey(LoadChangeKind kind);

struct LoadChange {
  LoadChangeKind kind = LoadChangeKind::DegenerateFace;
  uint32_t object = 0;  ///< index into Scene::objects (the face's object when it was read)
  Vec3 position;        ///< metres: the centroid of the face's finite corners (NaN when none is finite)
  std::string reason;   ///< "zero area", "a corner is not finite", …
};

struct LoadChanges {
  static constexpr size_t kListedPerKind = 20;
  std::array<size_t, kLoadChangeKinds> counts{};
  std::vector<LoadChange> listed;  ///< the first kListedPerKind of each kind, in loading order

  void record(LoadChangeKind kind, uint32_t object, const Vec3 &position, std::string reason);
  size_t count(LoadChangeKind kind) const { return counts[size_t(kind)]; }
};

/// The centroid of the finite points among `corners`, metres (NaN when none is finite).
Vec3 finiteCentroid(std::span<const Vec3> corners);

}  // namespace radiant
