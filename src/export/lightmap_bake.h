// A radiosity solution baked into a lightmap: the texels of an atlas
// (export/lightmap_atlas.h) filled from the solution read on the surface
// (docs/export.md, "Lightmaps").
//
// Each texel is the mean of samples × samples points spread over it (a box
// filter: a shadow edge crossing a texel gives it the covered fraction). A
// point inside one of the chart's triangles reads the solution exactly as
// the `interpolate` display does (radiosity/solution_query.h): B̂ and ρ̄
// interpolated from the element's nodes, the irradiance H = (B̂ − E)/ρ̄
// (the elements' own H where ρ̄ is nearly 0), and the radiance
// L = (E + ρ(x)·H)/π with ρ(x) the material's texture there (C&W eq. 9.11).
//
// Texels no sample of which falls inside a triangle (the padding around a
// chart, and the rim of texels a chart's edge only grazes) are then
// dilated: ring after ring, each takes the mean of its covered eight
// neighbours, so that bilinear filtering and the first mipmaps never read
// black across a chart's edge or a seam.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "export/lightmap_atlas.h"
#include "radiosity/solution.h"
#include "scene/scene.h"

namespace radiant {

struct LightmapBakeOptions {
  int samples = 3;   ///< per texel side: samples² points a texel
  int dilation = 8;  ///< rings of texels filled beyond the charts (at least the atlas's padding)
};

struct LightmapImages {
  int width = 0, height = 0;
  std::vector<float> irradiance;  ///< 3 per texel, row 0 at the top: H arriving at the front, W·m⁻² (linear RGB)
  std::vector<float> radiance;    ///< 3 per texel: L leaving the front, W·sr⁻¹·m⁻², emission included
  std::vector<uint8_t> covered;   ///< per texel: 1 where a sample fell inside a triangle, 2 dilated, 0 empty
  size_t coveredTexels = 0;       ///< texels with covered == 1
};

/// The scene's triangles that carry light: both sides of a two-sided face,
/// faces with a radiosity patch only (not mirrors, glass or the hidden
/// pieces the mesh leaves out), in face order.
std::vector<LightmapTriangle> lightmapTriangles(const Scene &scene, const Solution &solution);

/// Fills the atlas's texels from the solution. `triangles` as given to buildLightmapAtlas.
LightmapImages bakeLightmap(const Scene &scene, const Solution &solution, std::span<const LightmapTriangle> triangles,
                            const LightmapAtlas &atlas, const LightmapBakeOptions &options = {});

}  // namespace radiant
