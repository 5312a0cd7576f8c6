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

#include "radiosity/solution.h"
#include "scene/scene.h"

namespace radiant {

/// The triangles of one material, indexed, counter-clockwise from the front.
struct BakedPrimitive {
  uint32_t material = 0;
  bool hasUv = false;  ///< the material has a diffuse texture and the faces texture coordinates
  // Per vertex, tightly packed floats:
  std::vector<float> positions;   ///< 3: metres
  std::vector<float> normals;     ///< 3: the front side's unit normal
  std::vector<float> uvs;         ///< 2: the material's texture coordinates (uvScale applied, v up); hasUv only
  std::vector<float> radiance;    ///< 3: L = max(B, E)/π, W·sr⁻¹·m⁻², RGB
  std::vector<float> irradiance;  ///< 3: H arriving at the front, W·m⁻²
  std::vector<float> colour;      ///< 3: display-linear T(L)/ρ̄ in [0, 1] (docs/export.md)
  std::vector<uint32_t> indices;  ///< 3 per triangle

  size_t vertexCount() const { return positions.size() / 3; }
  size_t triangleCount() const { return indices.size() / 3; }
};

struct BakedMesh {
  std::vector<BakedPrimitive> primitives;  ///< in material order, only materials with triangles
  size_t elements = 0;                     ///< radiosity elements baked
};

/// Display-linear values (tone operator and gamut rule, display/display_mapping.h)
/// of a radiance, each channel in [0, 1].
using DisplayLinearFunction = std::function<void(const float radiance[3], double display[3])>;

/// Bakes an RGB scene's solution. Faces the mesh leaves out are written as
/// their input triangles with no light when their material is a mirror or
/// glass (so the geometry is complete), and left out otherwise (the hidden
/// pieces of faces cut where other surfaces meet them, mesh/face_split.h).
BakedMesh bakeSolution(const Scene &scene, const Solution &solution, const DisplayLinearFunction &displayLinear);

}  // namespace radiant
