// Pieces shared by the JSON scene loader and the OBJ loader; not a public API.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "scene/json_reader.h"
#include "scene/scene.h"
#include "util/error.h"

namespace radiant::detail {

/// Index of the material named "default" (Lambertian, ρ = 0.5), added on first use.
uint32_t defaultMaterialIndex(Scene &scene);

/// Index of the material called `name`, or −1.
int findMaterial(const Scene &scene, const std::string &name);

/// Items (materials, lights) by name, for a loader that looks names up per
/// face or per entry: a scan of every name (findMaterial) made an OBJ of 10⁵
/// usemtl materials, or a scene of 10⁵ luminaires, quadratic (issue 38). The
/// index catches up with the items appended since its last lookup, so a
/// loader that pushes to the scene's vector keeps no second list; of two
/// equal names the first wins, as in findMaterial.
template <typename Item>
class NameIndex {
 public:
  explicit NameIndex(const std::vector<Item> &items) : items_(items) {}
  /// Index of the item called `name`, or −1.
  int find(const std::string &name) {
    if (items_.size() < indexed_) byName_.clear(), indexed_ = 0;  // items were removed: start over
    for (; indexed_ < items_.size(); ++indexed_, ++namesHashed_) byName_.emplace(items_[indexed_].name, int(indexed_));
    const auto it = byName_.find(name);
    return it == byName_.end() ? -1 : it->second;
  }
  /// The names put into the index so far: the work done, linear in the items
  /// however many lookups were made (tests count it).
  size_t namesHashed() const { return namesHashed_; }

 private:
  const std::vector<Item> &items_;
  std::unordered_map<std::string, int> byName_;
  size_t indexed_ = 0, namesHashed_ = 0;
};
using MaterialNames = NameIndex<Material>;
using LightNames = NameIndex<PointLight>;

/// Throws InputError at `where` for a value the later stages cannot use:
/// non-finite or negative values, a diffuse reflectance ≥ 1 in any band
/// (radiosity's Neumann series would diverge), a specular reflectance or
/// transmittance > 1, glossy diffuse + specular > 1, ior ≤ 0, roughness ∉ (0, 1].
/// `field` names the offending key in each message ("reflectance", "Kd", …)
/// through `names`.
struct MaterialFieldNames {
  const char *diffuse = "reflectance";
  const char *specular = "specular";
  const char *emission = "emission";
  const char *ior = "ior";
  const char *roughness = "roughness";
  /// MTL: the line of each statement ("Kd" → 12), so that a bad value is
  /// reported at its own line rather than at newmtl's.
  std::map<std::string, int> lines;
  const char *transmittance = "diffuse_transmittance";
  const char *transmissionRoughness = "roughness";  ///< a dielectric's GGX α
};
void checkMaterial(const Material &material, const InputLocation &where, const MaterialFieldNames &names = {});

/// Adds an input polygon whose vertices are already in scene.positions (and
/// uvs/normals, −1 when absent). Triangles and planar convex quads become one
/// face; a non-planar or non-convex quad becomes two triangles split along a
/// diagonal that keeps both inside the outline; a polygon of more than four
/// vertices is fan-split into triangles. `flipWinding` reverses the order (for a
/// mirroring transform), keeping the first vertex first. Degenerate pieces are
/// dropped and counted by Scene::addFace.
void addPolygon(Scene &scene, const std::vector<uint32_t> &vertices, const std::vector<int32_t> &uvs,
                const std::vector<int32_t> &normals, uint32_t material, uint32_t object, bool flipWinding);

/// Removes every face that repeats an earlier one exactly (the same corner
/// positions in the same cyclic order), with its triangles, and says so in
/// one warning.
void dropRepeatedFaces(Scene &scene);

/// A UV sphere with `segments` slices around the axis and segments/2 stacks,
/// outward-facing, with per-vertex normals (smooth shading) and uvs (u around
/// the y axis, v from the south pole), transformed by `toWorld`.
void addUvSphere(Scene &scene, const Vec3 &center, double radius, int segments, const Transform &toWorld,
                 uint32_t material, uint32_t object);

/// appendObj with the context of a JSON scene: `defaultMaterial` (or, when it is
/// −1, the material called `defaultMaterialName` from the MTL, or "default" when
/// that is empty) for faces without usemtl. `fileFrom` locates the JSON entry
/// for a file that cannot be opened, `materialFrom` the one for a default
/// material found neither in the scene nor in the MTL.
void appendObjFromScene(Scene &scene, const std::string &objPath, const Transform &toWorld,
                        const std::string &objectName, int defaultMaterial, const std::string &defaultMaterialName,
                        const InputLocation &fileFrom, const InputLocation &materialFrom);

/// What a glTF file says about the view (load_gltf.cpp).
struct GltfView {
  bool hasCamera = false;    ///< the scene has a perspective camera
  CameraSettings camera;     ///< that camera, placed by its node and the entry's transform
  double aspectRatio = 0;    ///< its width / height, 0 when the file does not say
  InputLocation cameraFrom;  ///< the camera's JSON path in the glTF file
};

/// Appends the meshes of a glTF 2.0 file's scene (.gltf or .glb, docs/scene-format.md),
/// transformed by `toWorld`: one SceneObject per node with a mesh, named
/// `objectName/NODE`. Primitives without a material get `defaultMaterial`
/// (−1: "default"); a glTF material named like one of the scene's first
/// `overridableMaterials` materials (the JSON scene's) is replaced by it.
/// `fileFrom` locates the reference to a file that cannot be opened; every
/// other error names the glTF file and the JSON path in it.
GltfView appendGltf(Scene &scene, const std::string &path, const Transform &toWorld, const std::string &objectName,
                    int defaultMaterial, size_t overridableMaterials, const InputLocation &fileFrom);

// Lights (load_lights.cpp; docs/luminaires.md).
/// The JSON "lights": point and spot lights, positions in scene units (× metres).
void parseLights(Scene &scene, const JsonNode &lights, double metres);
/// The JSON "luminaires": photometric files (IES, EULUMDAT) resolved against `directory`.
void parseLuminaires(Scene &scene, const JsonNode &luminaires, double metres, const std::filesystem::path &directory);

// Spectral scenes (load_spectral.cpp).
/// A material value {"spectrum": [[nm, value], …], "scale": s}.
SampledSpectrum parseSpectrum(const JsonNode &node);
/// The top-level "spectral" block: "wavelengths", or "range" and "samples".
SpectralSettings parseSpectralSettings(const JsonNode &node);
/// 16 samples, 400–700 nm every 20 nm: for a scene that gives spectra but no "spectral" block.
SpectralSettings defaultSpectralSettings();
/// True when a value in the JSON "materials" object is a spectrum.
bool materialsGiveSpectra(const JsonNode &materials);
/// The per-band value at `key`: a number (grey), three numbers (RGB scenes
/// only) or a spectrum (stored in `spectrum`); `fallback` when absent.
Bands parseBandValue(const JsonNode &material, const std::string &key, const Bands &fallback, bool spectralScene,
                     std::optional<SampledSpectrum> &spectrum);
/// Range checks of a material's spectra at their samples.
void checkSpectra(const Material &material, const InputLocation &where, const MaterialFieldNames &names = {});
/// After loading a spectral scene: every material is grey or spectral, glossy
/// sums ≤ 1 at every wavelength; then the bands get the spectra's sRGB colour.
/// Messages name each material where it was defined (Material::definedAt).
void checkSpectralScene(Scene &scene);

/// Loads every image the materials name into Scene::textures (each file once
/// per encoding and wrap) and sets the materials' texture indices. A file that
/// cannot be read is an InputError at the MTL line or JSON path that named it.
void loadTextures(Scene &scene);

/// Camera and image/render settings checks shared by the JSON loader and validateScene.
void checkCamera(const CameraSettings &camera, const InputLocation &where);
void checkRenderSettings(const RenderSettings &render, const InputLocation &where);

/// A camera that frames the scene's bounding box from the +z side (fov 40°).
CameraSettings frameBounds(const Scene &scene);

}  // namespace radiant::detail
