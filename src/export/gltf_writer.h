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

/// Writes `baked` (with the scene's materials, textures and camera) to
/// `path`: binary glTF for .glb, JSON with data: URIs for .gltf. Atomic: a
/// failure leaves no partial file. Throws InputError when a texture file
/// cannot be read, std::runtime_error when the file cannot be written.
void writeGltf(const Scene &scene, const BakedMesh &baked, const ExportProvenance &provenance, const std::string &path);

}  // namespace radiant
