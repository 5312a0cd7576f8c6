// A lightmap's texture layout: the scene's own triangles cut into charts,
// each chart flattened onto its plane and packed into one atlas without
// overlap (docs/export.md, "Lightmaps").
//
// Charts follow the surfaces a baker would want whole: connected triangles
// whose normals lie within a cone of the chart's first (largest) triangle's,
// so that a planar polygon group becomes one chart and a curved tessellated
// surface is cut into patches of at most `maxChartAngleDegrees` of bending,
// as xatlas (Young, 2016–) and Lévy et al.'s LSCM charts do by normal
// deviation. A chart is flattened by projection onto the plane of its mean
// normal: exact on a plane; on a curved chart a texel covers at most
// 1/cos(angle) of its nominal area (15 % at 30°), and no triangle flips. A
// chart that would still cover itself in projection (a ramp winding round
// within the cone) is grown again with half the angle until it does not.
//
// Each chart is turned to the smallest bounding rectangle (one of its convex
// hull's edge directions, Freeman & Shapira 1975), scaled to the texel size,
// snapped to whole texels, and placed by a shelf packer (tallest first),
// `padding` texels apart and from the atlas's border. A rectangle never
// overlaps another, so neither do the charts.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "util/math.h"

namespace radiant {

/// One triangle of the geometry to lay out, counter-clockwise from its front.
/// (`face` and `triangle` are the bake's: the atlas reads only the corners.)
struct LightmapTriangle {
  Vec3 corners[3];
  uint32_t face = 0;      ///< the scene face it belongs to (a two-sided face's back is a face of its own)
  uint32_t triangle = 0;  ///< its Scene::triangles entry (texture coordinates, material)
};

struct AtlasOptions {
  /// Metres per texel; 0: chosen so that the atlas fits `size` × `size`.
  double texelSize = 0;
  /// The atlas's side in texels when texelSize is 0.
  int size = 1024;
  /// Texels between two charts, and between a chart and the atlas's edge:
  /// what bilinear filtering and the first mipmaps read beyond a chart.
  int padding = 4;
  /// Largest angle between a chart triangle's normal and the chart's first.
  double maxChartAngleDegrees = 30;
};

struct LightmapChart {
  std::vector<uint32_t> triangles;  ///< indices into the input
  int x = 0, y = 0;                 ///< the chart's rectangle in the atlas: first texel column and row
  int width = 0, height = 0;        ///< in texels, padding not included
};

struct LightmapAtlas {
  int width = 0, height = 0;  ///< texels
  double texelSize = 0;       ///< metres per texel
  std::vector<LightmapChart> charts;
  /// Per input triangle and corner, the lightmap coordinates (u, v) in texels
  /// from the atlas's top-left corner: 6 per triangle. Divide by width and
  /// height for glTF's TEXCOORD_1.
  std::vector<double> texelCoordinates;
  std::vector<int32_t> chartOfTriangle;  ///< per input triangle; −1 for a degenerate one (no area)
};

/// The largest atlas side buildLightmapAtlas accepts, in texels: the bake
/// holds 25 bytes a texel (400 MB at this size), and engines' lightmaps stop here.
constexpr int kMaxLightmapSide = 4096;

/// Lays out `triangles`. Throws InputError when the atlas would exceed
/// kMaxLightmapSide texels a side (a texel size far too small for the scene).
LightmapAtlas buildLightmapAtlas(std::span<const LightmapTriangle> triangles, const AtlasOptions &options);

}  // namespace radiant
