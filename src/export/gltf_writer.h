// A baked radiosity solution as glTF 2.0 (.glb, or .gltf with its buffers
// embedded): the file format of docs/export.md, written with Debian's
// tinygltf.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "export/baked_mesh.h"
#include "scene/scene.h"

namespace radiant {

/// What the file says about how it was made (asset.extras.radiant).
struct ExportProvenance {
  std::string solver;        ///< the solution's solver
  std::string toneOperator;  ///< the display mapping COLOR_0 was made with
  std::vector<std::pair<std::string, double>> toneParameters;
  std::string adaptedTo;  ///< the operator's constants, read from the camera's view (DisplayMapping::describe)
};

/// A lightmap for a mesh whose primitives carry lightmapUvs (export/lightmap_mesh.h),
/// its two images encoded (export/lightmap_encoding.h).
struct GltfLightmap {
  std::vector<unsigned char> displayPng;     ///< sRGB T(L): the unlit base colour plain viewers show
  std::vector<unsigned char> irradiancePng;  ///< RGBE H, W·m⁻²: what engines multiply their albedo by (ρ·H/π)
  int width = 0, height = 0;                 ///< texels
  double texelSize = 0;                      ///< metres
  size_t charts = 0;
  double utilisation = 0;  ///< covered texels over all
};

/// Writes `baked` (with the scene's materials, textures and camera) to
/// `path`: binary glTF for .glb, JSON with data: URIs for .gltf. Atomic: a
/// failure leaves no partial file. Throws InputError when a texture file
/// cannot be read, std::runtime_error when the file cannot be written.
/// With `lightmap`, the primitives with lightmap coordinates are drawn with
/// it (docs/export.md, "Lightmaps": unlit, its display image as the base
/// colour on TEXCOORD_1; the irradiance and the material's own colour in the
/// RADIANT_lightmap extension).
void writeGltf(const Scene &scene, const BakedMesh &baked, const ExportProvenance &provenance, const std::string &path,
               const GltfLightmap *lightmap = nullptr);

}  // namespace radiant
