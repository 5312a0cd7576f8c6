// Pieces of the MGF 2.0 reader (load_mgf.cpp) shared by its files; not a public API.
//
// The Materials and Geometry Format (G. Ward, LBNL, 1995; 2.0 adds `fh` faces
// with holes): one entity per line, contexts for colour, material, vertex,
// transform and object. docs/scene-format.md#mgf-scenes lists what Radiant makes of each entity.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "colour/spectrum.h"
#include "scene/scene.h"
#include "util/error.h"

namespace radiant::detail {

// ---- the file's entities (mgf_entities.cpp) ----

/// One entity: its words (keyword first), and the line it starts on.
struct MgfEntity {
  std::vector<std::string> words;
  int line = 0;
};
/// At most this many words in an entity (a cspec or an fh of many corners).
constexpr size_t kMaxMgfEntityWords = size_t(1) << 16;
/// The file's entities, comments dropped and continued lines (`\` at the end)
/// joined: a regular file of at most 1 GiB (util/input_file.h), else an
/// InputError naming it at `from`.
std::vector<MgfEntity> readMgfEntities(const std::string &path, const InputLocation &from);

// ---- colours and materials (mgf_material.cpp) ----

/// An MGF colour: a chromaticity, and a spectrum when it was given as one
/// (cspec, cct, or a cmix of such). Its luminance is normalised to Y = 1: the
/// reflectance or emittance that uses it gives the amount.
struct MgfColour {
  double x = 1.0 / 3.0, y = 1.0 / 3.0;      ///< CIE 1931 chromaticity; the default is equal-energy white
  std::optional<SampledSpectrum> spectrum;  ///< relative, Y = 1 over 380–780 nm
};

/// cxy x y; cspec λmin λmax v…; cct T; cmix w c w c …. Each throws InputError at `where`.
MgfColour mgfColourFromChromaticity(double x, double y, const InputLocation &where);
MgfColour mgfColourFromSpectrum(double firstNm, double lastNm, const std::vector<double> &values,
                                const InputLocation &where);
MgfColour mgfColourFromTemperature(double kelvin, const InputLocation &where);
MgfColour mgfColourMix(const std::vector<std::pair<double, MgfColour>> &parts, const InputLocation &where);

/// Linear sRGB of a colour with luminance 1, the equal-energy white adapted to
/// D65 (Bradford) so that MGF's neutral colour is grey. Negative components
/// (colours outside the sRGB gamut) are clipped to 0; `clipped` says so.
Bands mgfColourToLinearSrgb(const MgfColour &colour, bool &clipped);

/// An MGF material context (the m entity and what follows it).
struct MgfMaterial {
  int sides = 1;
  double rd = 0, td = 0, ed = 0, rs = 0, rsAlpha = 0, ts = 0, tsAlpha = 0;
  double iorReal = 1, iorImaginary = 0;
  MgfColour rdColour, tdColour, edColour, rsColour, tsColour;
  uint64_t version = 0;  ///< incremented by every change, so a changed material becomes a new Radiant material
};

/// Whether two MGF materials hold the same values (their versions aside).
bool sameMgfValues(const MgfMaterial &a, const MgfMaterial &b);

/// The Radiant material for an MGF material (docs/scene-format.md#mgf-materials);
/// simplifications are added to `warnings`, prefixed with `where`. In a
/// `spectral` scene every value gets its colour's spectrum (a neutral cxy
/// colour a constant one; any other cxy colour is an InputError at `where`).
Material mgfToMaterial(const MgfMaterial &mgf, const std::string &name, const InputLocation &where,
                       std::vector<std::string> &warnings, bool spectral = false);

// ---- geometry (mgf_geometry.cpp) ----

/// A point of MGF geometry in the file's own coordinates, with an optional normal.
struct MgfPoint {
  Vec3 position;
  Vec3 normal;
  bool hasNormal = false;
};

/// Where the geometry goes: the scene, the transform to metres, the face's
/// material and object, and the tessellation tolerance.
struct MgfTarget {
  Scene &scene;
  Transform toWorld;
  uint32_t material = 0;
  uint32_t object = 0;
  /// Largest distance of a tessellated curved surface from the true one, as a
  /// fraction of its radius (the sagitta of one slice's chord).
  double tolerance = 1e-3;
};

/// Slices around a circle so that the chord's sagitta is at most `tolerance` × radius (8 … 1024, even).
int mgfSlicesForTolerance(double tolerance);

/// f / fh: a polygon (counter-clockwise from the front) with holes. Triangles
/// and quads go to addPolygon; larger polygons and any with holes are
/// triangulated by ear clipping after joining the holes to the outline.
/// Throws InputError at `where` for a polygon it cannot triangulate.
void mgfAddFace(const MgfTarget &target, const std::vector<MgfPoint> &outline,
                const std::vector<std::vector<MgfPoint>> &holes, const InputLocation &where);

/// The primitives, in the file's coordinates (a negative radius or length
/// faces inwards, as the specification says). Arguments are checked by the caller.
void mgfAddSphere(const MgfTarget &target, const Vec3 &centre, double radius);
void mgfAddCone(const MgfTarget &target, const Vec3 &base, double baseRadius, const Vec3 &apex, double apexRadius);
void mgfAddRing(const MgfTarget &target, const Vec3 &centre, const Vec3 &axis, double innerRadius, double outerRadius);
void mgfAddTorus(const MgfTarget &target, const Vec3 &centre, const Vec3 &axis, double innerRadius, double outerRadius);
void mgfAddPrism(const MgfTarget &target, const std::vector<Vec3> &base, double length, const InputLocation &where);

/// Appends an MGF file (docs/scene-format.md#mgf-scenes) transformed by
/// `toWorld`: one SceneObject per MGF object (`o`), named
/// `objectName/OBJECT/…`, and `objectName` for geometry outside any object.
/// Errors name the MGF file and line.
void appendMgf(Scene &scene, const std::string &path, const Transform &toWorld, const std::string &objectName,
               const InputLocation &fileFrom);

}  // namespace radiant::detail
