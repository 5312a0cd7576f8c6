// The radiosity solution as triangles with light at their vertices: what the
// exporters (glTF, PLY) write, and what a real-time viewer draws (C&W §9.7:
// a view-independent solution displayed by graphics hardware).
//
// Vertices are the mesh's nodes, with the values the `interpolate` display
// reads there (radiosity/solution_query.h). A quadrilateral element becomes
// four triangles around a centre vertex holding the mean of its corners (the
// value bilinear interpolation has at the centre): a renderer that
// interpolates linearly over triangles then stays close to the bilinear
// display, without the diagonal seams of a two-triangle split.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "colour/spectrum.h"
#include "radiosity/solution.h"
#include "scene/scene.h"

namespace radiant {

/// The triangles of one material, indexed, counter-clockwise from the front.
struct BakedPrimitive {
  uint32_t material = 0;
  bool hasUv = false;  ///< the material has a diffuse texture and the faces texture coordinates
  // Per vertex, tightly packed floats:
  std::vector<float> positions;    ///< 3: metres
  std::vector<float> normals;      ///< 3: the front side's unit normal
  std::vector<float> uvs;          ///< 2: the material's texture coordinates (uvScale applied, v up); hasUv only
  std::vector<float> lightmapUvs;  ///< 2: a lightmap's coordinates, (0, 0) its top-left corner (lightmap_mesh.h)
  // Light at the vertices: the per-vertex export's (a lightmapped mesh leaves them empty, but for black colours).
  std::vector<float> radiance;     ///< 3: L = max(B, E)/π, W·sr⁻¹·m⁻², RGB
  std::vector<float> irradiance;   ///< 3: H arriving at the front, W·m⁻²
  std::vector<float> reflectance;  ///< 3: ρ̄, the mean reflectance the solution used there (not written)
  std::vector<float> colour;       ///< 3: display-linear T(L)/ρ̄ in [0, 1] (docs/export.md)
  std::vector<uint32_t> faces;     ///< 1: the scene face the vertex lies on (not written)
  std::vector<uint32_t> indices;   ///< 3 per triangle

  size_t vertexCount() const { return positions.size() / 3; }
  size_t triangleCount() const { return indices.size() / 3; }
};

struct BakedMesh {
  std::vector<BakedPrimitive> primitives;  ///< in material order, only materials with triangles
  size_t elements = 0;                     ///< radiosity elements baked
};

/// Below this ρ̄ a band reflects (almost) nothing: its irradiance cannot be
/// recovered from B − E, and is taken from the elements' own H instead.
constexpr double kSmallestReflectance = 1e-4;

/// What a point of a patch carries, as the `interpolate` display reads it
/// there: L = max(B̂, E)/π (ambient included), H such that ρ̄H = B̂ − E (the
/// elements' own H + ambient where ρ̄ is below kSmallestReflectance), and ρ̄,
/// so that E + ρ(x)·H reproduces C&W eq. 9.11's E + (B̂ − E)·ρ(x)/ρ̄.
struct SurfaceLight {
  Bands radiance, irradiance, reflectance;
};

/// The elements' H + ambient at the nodes: surfaceLightAt's fallback irradiance.
std::vector<Bands> nodeIrradiance(const Solution &solution);

/// The light at a location of the solution's mesh, interpolated from its
/// element's nodes; `nodeIrradiance` from nodeIrradiance(solution), `emitted`
/// the material's exitance E (π L_e).
SurfaceLight surfaceLightAt(const Solution &solution, const std::vector<Bands> &nodeIrradiance, const MeshLocation &at,
                            const Bands &emitted);

/// Display-linear values (tone operator and gamut rule, display/display_mapping.h)
/// of a radiance, each channel in [0, 1].
using DisplayLinearFunction = std::function<void(const float radiance[3], double display[3])>;

/// Bakes a solution of the scene (an RGB scene's, or one spectral pass's at
/// the scene's current bands). Faces the mesh leaves out are written as
/// their input triangles with no light when their material is a mirror or
/// glass (so the geometry is complete), and left out otherwise (the hidden
/// pieces of faces cut where other surfaces meet them, mesh/face_split.h).
/// With `displayLinear`, the colours too (applyDisplayColours).
BakedMesh bakeSolution(const Scene &scene, const Solution &solution, const DisplayLinearFunction &displayLinear = {});

/// Sets every vertex's colour: COLOR_0 = T(L)/ρ̄ per channel, clamped to
/// [0, 1]: an unlit viewer multiplies it by the base colour ρ, and shows T(L).
void applyDisplayColours(BakedMesh &baked, const DisplayLinearFunction &displayLinear);

/// The light of another solution of the same scene (a spectral pass's, whose
/// adaptive mesh differs) at `baked`'s vertices: read at each vertex's place
/// as the `interpolate` display reads it. Vertices on faces without a patch
/// (mirrors, glass) stay dark. `scene` at that solution's bands.
BakedMesh resampleLight(const BakedMesh &baked, const Scene &scene, const Solution &solution);

/// A spectral scene's passes at the same vertices (the first pass baked, the
/// others resampled onto it: resampleLight) as one RGB mesh:
/// radiance and irradiance in linear sRGB from the spectrum (CIE 1931, then
/// `balance`, as render/spectral_film.h forms an image's colour), ρ̄ the
/// ratio of the reflected light's colour to the irradiance's (the
/// material's colour where no light arrives). `scene` holds its colours
/// (applySpectralColour). Colours are not set.
BakedMesh combineSpectralPasses(const std::vector<BakedMesh> &passes, const Scene &scene, WhiteBalance balance);

}  // namespace radiant
