// The scene's own triangles with a second set of texture coordinates into a
// lightmap (export/lightmap_atlas.h): what `radiant export --lightmap`
// writes, where the per-vertex export (export/baked_mesh.h) writes the
// radiosity mesh instead (docs/export.md, "Lightmaps").
#pragma once

#include <span>

#include "export/baked_mesh.h"
#include "export/lightmap_atlas.h"

namespace radiant {

/// One primitive per material: the lightmap's triangles with TEXCOORD_1
/// (BakedPrimitive::lightmapUvs) and, where the material has a texture,
/// TEXCOORD_0; a vertex is shared by the triangles of one chart that meet
/// at it. Mirrors and glass, which have no light of their own in the
/// solution, follow as their input triangles without lightmap coordinates
/// and with black vertex colours, as bakeSolution writes them (those not
/// among `triangles`). `elements` is the solution's element count, for the
/// file's record.
BakedMesh lightmapMesh(const Scene &scene, std::span<const LightmapTriangle> triangles, const LightmapAtlas &atlas,
                       size_t elements);

}  // namespace radiant
