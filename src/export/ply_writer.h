// A baked radiosity solution as a binary PLY mesh (Turk's polygon file
// format), for MeshLab, Blender and CloudCompare: one mesh, vertex colours
// that are the display's (the tone operator, gamut rule and sRGB curve of
// display/display_mapping.h, 8 bits), plus the linear radiance and irradiance
// as float properties that those programs keep as custom attributes.
#pragma once

#include <string>

#include "export/baked_mesh.h"

namespace radiant {

/// Writes `baked` to `path` atomically. `display` maps a radiance to its
/// sRGB-encoded display value in [0, 1] (DisplayMapping::encode).
void writePly(const BakedMesh &baked, const DisplayLinearFunction &display, const std::string &path);

}  // namespace radiant
