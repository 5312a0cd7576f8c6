// The scene as plain data: what every later stage reads.
//
// Geometry is in metres (loaders convert declared units), radiometry in SI.
// Input polygons are kept as faces (triangles and planar quads) because the
// radiosity mesher subdivides quads as quads; the ray tracer sees the same
// faces as triangles, listed in `triangles`.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "scene/camera.h"
#include "scene/light.h"
#include "scene/load_changes.h"
#include "scene/material.h"
#include "util/math.h"

namespace radiant {

/// One input polygon (3 or 4 vertices, counter-clockwise seen from the front).
/// The largest coordinate a vertex or the camera may have, in metres. The
/// ray tracer (Embree) works in single precision, where 10⁹ m already has a
/// resolution of 64 m, and refuses (aborts on) rays from beyond 1.8·10¹⁸.
constexpr double kMaxCoordinateMetres = 1e9;
/// Every coordinate of `p` (metres) within ±kMaxCoordinateMetres; false for NaN.
inline bool withinCoordinateRange(const Vec3 &p) {
  return std::abs(p.x) <= kMaxCoordinateMetres && std::abs(p.y) <= kMaxCoordinateMetres &&
         std::abs(p.z) <= kMaxCoordinateMetres;
}

struct Face {
  int vertexCount = 3;
  uint32_t vertices[4] = {0, 0, 0, 0};    ///< indices into Scene::positions
  int32_t uvs[4] = {-1, -1, -1, -1};      ///< indices into Scene::uvs, or −1
  int32_t normals[4] = {-1, -1, -1, -1};  ///< indices into Scene::normals, or −1
  uint32_t material = 0;
  uint32_t object = 0;
  /// Two-sided surfaces (Material::twoSided) are a pair of faces back to back:
  /// the face as given and its back, the same polygon wound the other way
  /// (added by Scene::addBackFaces). `twin` is the other face of the pair, −1
  /// for a one-sided face; `back` marks the added one. Each side is its own
  /// radiosity patch; the ray tracer and the face tree hold only the front's
  /// geometry and report a hit from behind it as a hit on its back.
  int32_t twin = -1;
  bool back = false;
};

/// One triangle as the ray tracer sees it; `face` is the input polygon it came from.
struct Triangle {
  uint32_t v[3];
  int32_t uv[3];
  int32_t n[3];
  uint32_t face;
  uint32_t material;
};

/// An input object: a JSON object entry, or an OBJ object/group. Reports are per object.
struct SceneObject {
  std::string name;
  std::string source;  ///< file (and group) it came from, for messages
};

/// Limits that reject absurd requests before any large allocation.
constexpr int kMaxImageDimension = 16384;
constexpr long long kMaxImagePixels = 1LL << 26;
constexpr int kMaxSamplesPerPixel = 1 << 20;

struct RenderSettings {
  int width = 512;
  int height = 512;
  int samplesPerPixel = 64;
  double timeBudgetSeconds = 0;  ///< 0: no budget
  uint64_t seed = 1;
  int maxDepth = 0;     ///< 0: unlimited (Russian roulette ends paths)
  double exposure = 0;  ///< PNG exposure in stops
};

/// The sample wavelengths of a spectral scene (docs/spectral.md). The solution
/// and every renderer run at these wavelengths, three at a time (one pass per
/// three, in the RGB machinery's three bands); colour is formed at display.
struct SpectralSettings {
  std::vector<double> wavelengths;  ///< nm, strictly increasing; empty: an RGB scene
  bool enabled() const { return !wavelengths.empty(); }
  int passCount() const { return (int(wavelengths.size()) + kBandCount - 1) / kBandCount; }
  /// Wavelength of band `band` in pass `pass`; the last pass repeats the last wavelength in its unused bands.
  double wavelength(int pass, int band) const {
    return wavelengths[std::min(size_t(pass) * kBandCount + band, wavelengths.size() - 1)];
  }
};

/// The most points one calculation grid may have (nu·nv).
constexpr long long kMaxGridPoints = 1000000;

/// A calculation grid (the JSON "grids", docs/scene-format.md): nu × nv
/// measuring points over the parallelogram origin + s·u + t·v, at the cell
/// centres s = (i + ½)/nu, t = (j + ½)/nv, each measuring the illuminance on
/// a plane facing `normal`. Metres, like every position.
struct CalculationGrid {
  std::string name;
  Vec3 origin, u, v;
  Vec3 normal;  ///< unit; the front of the measuring plane
  int nu = 1, nv = 1;
  /// Point (i, j), 0 ≤ i < nu, 0 ≤ j < nv: the centre of its cell.
  Vec3 point(int i, int j) const { return origin + u * ((i + 0.5) / nu) + v * ((j + 0.5) / nv); }
  size_t pointCount() const { return size_t(nu) * size_t(nv); }
};

struct Scene {
  std::string sourceFile;  ///< the scene file, for messages and for solution files later
  /// Metres per scene unit (the JSON "units"); command-line camera positions are in scene units.
  double metresPerUnit = 1.0;

  std::vector<Vec3> positions;  ///< metres
  std::vector<Vec3> normals;    ///< unit, optional per-vertex shading normals
  std::vector<double> uvs;      ///< pairs (u, v)
  std::vector<Face> faces;
  std::vector<Triangle> triangles;
  std::vector<Material> materials;
  std::vector<Texture> textures;  ///< images named by the materials, each loaded once
  std::vector<SceneObject> objects;

  CameraSettings camera;
  RenderSettings render;
  SpectralSettings spectral;
  std::vector<CalculationGrid> grids;  ///< JSON scenes only; empty otherwise
  /// Point, spot and photometric lights (JSON scenes only), besides the emitting materials.
  std::vector<PointLight> lights;

  /// Degenerate faces dropped while loading (counted for the warning).
  size_t droppedDegenerateFaces = 0;
  /// What the loaders dropped or merged, by object and position (scene/load_changes.h).
  LoadChanges loadChanges;
  /// Counts a degenerate face as dropped and records where it was (`corners`
  /// in metres, as read: some may not be finite).
  void dropDegenerateFace(std::span<const Vec3> corners, uint32_t object, std::string reason);
  std::vector<std::string> warnings;

  /// Geometric normal of a triangle from its winding (front side).
  Vec3 triangleNormal(const Triangle &t) const {
    return normalize(cross(positions[t.v[1]] - positions[t.v[0]], positions[t.v[2]] - positions[t.v[0]]));
  }
  double triangleArea(const Triangle &t) const {
    return 0.5 * length(cross(positions[t.v[1]] - positions[t.v[0]], positions[t.v[2]] - positions[t.v[0]]));
  }
  /// Area of an input face (sum of its triangles).
  double faceArea(const Face &f) const;
  /// Newell normal of an input face (robust for slightly non-planar quads).
  Vec3 faceNormal(const Face &f) const;

  /// Adds a face, and its triangles; returns false (and counts it) when the face
  /// is degenerate (zero area or non-finite).
  bool addFace(const Face &face);
  /// A face's corners as positions, rotated to start at the smallest, in
  /// winding order or (`reversed`) the other way: two faces with equal keys
  /// are one surface facing the same way, or with a reversed key back to back.
  std::vector<std::array<double, 3>> cornerKey(const Face &f, bool reversed = false) const;
  /// Pairs the faces that are already back to back (the same corners in the
  /// reverse order: the later one becomes the back), then gives every other
  /// face of a two-sided material a back (Face::twin, Face::back) after all
  /// faces. validateScene calls it; a scene built in code calls it once its
  /// faces are in.
  void addBackFaces();
  /// The face that holds face f's geometry for the ray tracer and the face
  /// tree: f itself, or the front of a back face.
  uint32_t geometricFace(uint32_t f) const { return faces[f].back ? uint32_t(faces[f].twin) : f; }
};

}  // namespace radiant
