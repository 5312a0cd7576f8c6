#include "scene/load_changes.h"

#include <limits>

namespace radiant {

const char *loadChangeName(LoadChangeKind kind) {
  switch (kind) {
    case LoadChangeKind::DegenerateFace:
      return "degenerate face";
    case LoadChangeKind::RepeatedFace:
      return "repeated face";
    case LoadChangeKind::CollinearQuad:
      return "quad made a triangle";
    case LoadChangeKind::BackToBack:
      return "faces paired back to back";
  }
  return "?";
}

const char *loadChangeAction(LoadChangeKind kind) {
  return kind == LoadChangeKind::DegenerateFace || kind == LoadChangeKind::RepeatedFace ? "dropped" : "merged";
}

const char *loadChangeKey(LoadChangeKind kind) {
  switch (kind) {
    case LoadChangeKind::DegenerateFace:
      return "degenerate_faces";
    case LoadChangeKind::RepeatedFace:
      return "repeated_faces";
    case LoadChangeKind::CollinearQuad:
      return "collinear_quads";
    case LoadChangeKind::BackToBack:
      return "back_to_back_pairs";
  }
  return "?";
}

void LoadChanges::record(LoadChangeKind kind, uint32_t object, const Vec3 &position, std::string reason) {
  if (counts[size_t(kind)]++ < kListedPerKind) listed.push_back({kind, object, position, std::move(reason)});
}

Vec3 finiteCentroid(std::span<const Vec3> corners) {
  Vec3 sum;
  int finite = 0;
  for (const Vec3 &p : corners)
    if (isFinite(p)) sum += p, ++finite;
  if (finite == 0) return Vec3{1, 1, 1} * std::numeric_limits<double>::quiet_NaN();
  return sum / double(finite);
}

}  // namespace radiant
