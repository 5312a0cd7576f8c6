// radiant export --lightmap (docs/export.md, "Lightmaps"): the atlas has no
// overlaps and keeps its charts whole and undistorted; the texels hold the
// solution (a closed form in the furnace, the solution's own reading
// elsewhere, within what it changes over the texels a lookup reads); seams
// differ no more than the solution does; RGBE keeps 8 bits; the glTF file
// says what docs/export.md says it does.
#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <tiny_gltf.h>

#include <cmath>
#include <map>
#include <set>

#include "export/gltf_writer.h"
#include "export/lightmap_atlas.h"
#include "export/lightmap_bake.h"
#include "export/lightmap_encoding.h"
#include "export/lightmap_mesh.h"
#include "identity_display.h"
#include "radiosity/solver.h"
#include "scene/load_scene.h"
#include "temp_dir.h"
#include "test_scenes.h"
#include "util/random.h"

namespace radiant {
namespace {

Solution solveWith(const Scene &scene, double meshSize, double tolerance) {
  RayTracer tracer(scene);
  MeshOptions meshOptions;
  meshOptions.maxEdgeLength = meshSize;
  Solution s = initialSolution(scene, buildMesh(scene, meshOptions));
  SolverOptions options;
  options.solver = "gauss-seidel";
  options.tolerance = tolerance;
  solveRadiosity(tracer, s, options);
  return s;
}

/// A room with a tessellated sphere in it: curved charts, and a box's right angles.
Scene roomWithSphere(int segments) {
  return parseSceneJson(R"({
    "units": "metres",
    "camera": {"eye": [0.5, 0.5, 0.95], "target": [0.5, 0.4, 0.0], "up": [0, 1, 0], "fov": 60},
    "materials": {"wall": {"reflectance": 0.6}, "light": {"reflectance": 0.0, "emission": 5.0},
                  "grey": {"reflectance": 0.5}},
    "objects": [
      {"name": "floor", "type": "quad", "vertices": [[0,0,0],[0,0,1],[1,0,1],[1,0,0]], "material": "wall"},
      {"name": "ceiling", "type": "quad", "vertices": [[0,1,0],[1,1,0],[1,1,1],[0,1,1]], "material": "wall"},
      {"name": "lamp", "type": "quad", "vertices": [[0.4,0.95,0.4],[0.6,0.95,0.4],[0.6,0.95,0.6],[0.4,0.95,0.6]],
       "material": "light"},
      {"name": "z0", "type": "quad", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "material": "wall"},
      {"name": "z1", "type": "quad", "vertices": [[0,0,1],[0,1,1],[1,1,1],[1,0,1]], "material": "wall"},
      {"name": "x0", "type": "quad", "vertices": [[0,0,0],[0,1,0],[0,1,1],[0,0,1]], "material": "wall"},
      {"name": "x1", "type": "quad", "vertices": [[1,0,0],[1,0,1],[1,1,1],[1,1,0]], "material": "wall"},
      {"name": "ball", "type": "sphere", "center": [0.5, 0.3, 0.5], "radius": 0.25, "segments": )" +
                            std::to_string(segments) + R"(, "material": "grey"}
    ]})",
                        "room-with-sphere.json");
}

Vec3 normalOf(const LightmapTriangle &t) {
  return normalize(cross(t.corners[1] - t.corners[0], t.corners[2] - t.corners[0]));
}

/// Barycentrics of the 2D point (x, y) in the triangle of texel coordinates uv[0..5].
std::array<double, 3> barycentrics2d(const double *uv, double x, double y) {
  const double area = (uv[2] - uv[0]) * (uv[5] - uv[1]) - (uv[4] - uv[0]) * (uv[3] - uv[1]);
  const double b1 = ((x - uv[0]) * (uv[5] - uv[1]) - (uv[4] - uv[0]) * (y - uv[1])) / area;
  const double b2 = ((uv[2] - uv[0]) * (y - uv[1]) - (x - uv[0]) * (uv[3] - uv[1])) / area;
  return {1 - b1 - b2, b1, b2};
}

/// Rasterises TEXCOORD_1 at texel centres: a centre strictly inside triangles
/// of two charts, or of two triangles of one chart (a fold), is an overlap.
void expectNoOverlap(const LightmapAtlas &atlas, size_t triangleCount) {
  std::vector<int32_t> owner(size_t(atlas.width) * size_t(atlas.height), -1);
  std::vector<int32_t> ownerTriangle(owner.size(), -1);
  size_t overlaps = 0, covered = 0;
  for (size_t t = 0; t < triangleCount; ++t) {
    if (atlas.chartOfTriangle[t] < 0) continue;
    const double *uv = &atlas.texelCoordinates[6 * t];
    const int x0 = std::max(0, int(std::floor(std::min({uv[0], uv[2], uv[4]})))),
              x1 = std::min(atlas.width - 1, int(std::ceil(std::max({uv[0], uv[2], uv[4]})))),
              y0 = std::max(0, int(std::floor(std::min({uv[1], uv[3], uv[5]})))),
              y1 = std::min(atlas.height - 1, int(std::ceil(std::max({uv[1], uv[3], uv[5]}))));
    for (double c : {uv[0], uv[2], uv[4]}) ASSERT_TRUE(c >= 0 && c <= atlas.width) << "triangle " << t;
    for (double c : {uv[1], uv[3], uv[5]}) ASSERT_TRUE(c >= 0 && c <= atlas.height) << "triangle " << t;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const auto b = barycentrics2d(uv, x + 0.5, y + 0.5);
        if (std::min({b[0], b[1], b[2]}) <= 1e-9) continue;  // strictly inside only: shared edges are not overlaps
        const size_t texel = size_t(y) * size_t(atlas.width) + size_t(x);
        ++covered;
        if (owner[texel] >= 0) ++overlaps;
        owner[texel] = atlas.chartOfTriangle[t];
        ownerTriangle[texel] = int32_t(t);
      }
  }
  EXPECT_EQ(overlaps, 0u);
  EXPECT_GT(covered, 0u);
}

/// Chart rectangles lie inside the atlas, `padding` from its edges and from each other.
void expectPaddedRectangles(const LightmapAtlas &atlas, int padding) {
  for (size_t a = 0; a < atlas.charts.size(); ++a) {
    const LightmapChart &A = atlas.charts[a];
    EXPECT_GE(A.x, padding);
    EXPECT_GE(A.y, padding);
    EXPECT_LE(A.x + A.width + padding, atlas.width);
    EXPECT_LE(A.y + A.height + padding, atlas.height);
    for (size_t b = a + 1; b < atlas.charts.size(); ++b) {
      const LightmapChart &B = atlas.charts[b];
      const bool apart = A.x + A.width + padding <= B.x || B.x + B.width + padding <= A.x ||
                         A.y + A.height + padding <= B.y || B.y + B.height + padding <= A.y;
      EXPECT_TRUE(apart) << "charts " << a << " and " << b;
    }
  }
}

TEST(LightmapAtlas, EachPlanarFaceOfABoxIsOneUndistortedChart) {
  const int walls[6] = {0, 0, 0, 0, 0, 0};
  Scene scene = test::closedBox(2.0, walls);
  scene.materials.push_back(Material{});
  const Solution solution = solveWith(scene, 0.5, 1e-3);
  const std::vector<LightmapTriangle> triangles = lightmapTriangles(scene, solution);
  ASSERT_EQ(triangles.size(), 12u);
  AtlasOptions options;
  options.texelSize = 0.01;
  const LightmapAtlas atlas = buildLightmapAtlas(triangles, options);
  EXPECT_EQ(atlas.charts.size(), 6u);
  EXPECT_DOUBLE_EQ(atlas.texelSize, 0.01);
  // A planar chart is flattened without distortion: every edge is its length in texels.
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const double *a = &atlas.texelCoordinates[6 * t + 2 * size_t(k)];
      const double *b = &atlas.texelCoordinates[6 * t + 2 * size_t((k + 1) % 3)];
      const double metres = length(triangles[t].corners[(k + 1) % 3] - triangles[t].corners[k]);
      EXPECT_NEAR(std::hypot(b[0] - a[0], b[1] - a[1]) * atlas.texelSize, metres, 1e-9 * metres);
    }
  // Each 2 m face: 200 texels and one more, so that it lies half a texel inside its rectangle.
  for (const LightmapChart &chart : atlas.charts) {
    EXPECT_EQ(chart.width, 201);
    EXPECT_EQ(chart.height, 201);
  }
  expectNoOverlap(atlas, triangles.size());
  expectPaddedRectangles(atlas, options.padding);
}

TEST(LightmapAtlas, ACurvedSurfaceIsCutIntoChartsWithinTheNormalCone) {
  const Scene scene = roomWithSphere(24);
  const Solution solution = solveWith(scene, 0.25, 1e-3);
  const std::vector<LightmapTriangle> triangles = lightmapTriangles(scene, solution);
  AtlasOptions options;
  options.size = 512;
  const LightmapAtlas atlas = buildLightmapAtlas(triangles, options);
  EXPECT_EQ(atlas.width, 512);
  EXPECT_EQ(atlas.height, 512);
  // The sphere's 24²/2 faces in a few dozen charts, each within 2 × 30° of normal spread.
  const size_t sphereTriangles = triangles.size() - 14;  // the room: 7 quads
  EXPECT_GT(atlas.charts.size(), 7u + 6u);
  EXPECT_LT(atlas.charts.size(), 7u + sphereTriangles / 8);
  for (const LightmapChart &chart : atlas.charts)
    for (uint32_t a : chart.triangles)
      for (uint32_t b : chart.triangles)
        ASSERT_GE(dot(normalOf(triangles[a]), normalOf(triangles[b])), std::cos(60 * kPi / 180) - 1e-9);
  expectNoOverlap(atlas, triangles.size());
  expectPaddedRectangles(atlas, options.padding);
}

// A ramp winding round one and a half times (a car park's): every normal
// within a degree of vertical, so one cone would take it all, and its
// projection onto the horizontal would cover the first turn twice. The
// atlas must cut it into charts that do not fold.
TEST(LightmapAtlas, AChartThatWouldFoldOverItselfIsCut) {
  std::vector<LightmapTriangle> ramp;
  constexpr int kSteps = 90;
  constexpr double kTurns = 1.5, kRise = 0.05;  // metres per turn
  auto at = [&](double r, int step) {
    const double theta = 2 * kPi * kTurns * step / kSteps;
    return Vec3(r * std::cos(theta), kRise * theta / (2 * kPi), r * std::sin(theta));
  };
  for (int i = 0; i < kSteps; ++i) {
    const Vec3 a = at(1, i), b = at(2, i), c = at(2, i + 1), d = at(1, i + 1);
    ramp.push_back({{a, c, b}, 0, 0});  // counter-clockwise seen from above (+y)
    ramp.push_back({{a, d, c}, 0, 0});
  }
  for (const LightmapTriangle &t : ramp) ASSERT_GT(normalOf(t).y, std::cos(kPi / 180));
  AtlasOptions options;
  options.texelSize = 0.01;
  const LightmapAtlas atlas = buildLightmapAtlas(ramp, options);
  EXPECT_GE(atlas.charts.size(), 2u);
  expectNoOverlap(atlas, ramp.size());
  expectPaddedRectangles(atlas, options.padding);
}

TEST(LightmapAtlas, ATexelTooSmallForTheSceneIsAClearError) {
  const Scene scene = roomWithSphere(16);
  const Solution solution = solveWith(scene, 0.2, 1e-3);
  AtlasOptions options;
  options.texelSize = 1e-5;  // 10⁵ texels across a 1 m wall
  try {
    buildLightmapAtlas(lightmapTriangles(scene, solution), options);
    FAIL() << "no error";
  } catch (const InputError &e) {
    EXPECT_NE(std::string(e.what()).find("--texel-size"), std::string::npos) << e.what();
  }
}

// The furnace (every wall emits L_e = 1 and reflects ρ = ½): L = 2 W·sr⁻¹·m⁻²
// and H = π·2 W·m⁻² everywhere, so every texel, covered or dilated, holds
// exactly that; Gauss–Seidel to 1e-9 and float texels leave 1e-6.
TEST(LightmapBake, TheFurnaceFillsEveryTexelWithItsClosedForm) {
  const Scene scene = test::furnace(1.0, 0.5);
  const Solution solution = solveWith(scene, 0.25, 1e-9);
  const std::vector<LightmapTriangle> triangles = lightmapTriangles(scene, solution);
  AtlasOptions options;
  options.size = 128;
  const LightmapAtlas atlas = buildLightmapAtlas(triangles, options);
  const LightmapImages images = bakeLightmap(scene, solution, triangles, atlas);
  size_t dilated = 0;
  for (size_t i = 0; i < images.covered.size(); ++i) {
    if (!images.covered[i]) continue;
    dilated += images.covered[i] == 2;
    for (size_t c = 0; c < 3; ++c) {
      ASSERT_NEAR(images.radiance[3 * i + c], 2.0, 2e-6) << "texel " << i;
      ASSERT_NEAR(images.irradiance[3 * i + c], 2.0 * kPi, 1e-5) << "texel " << i;
    }
  }
  EXPECT_GT(images.coveredTexels, size_t(0.5 * 128 * 128));
  EXPECT_GT(dilated, 0u) << "the padding is filled";
}

/// The lightmap's bilinear lookup (texel centres at half-integers, clamped at the edges).
Bands bilinear(const LightmapImages &images, const std::vector<float> &values, double x, double y) {
  x -= 0.5, y -= 0.5;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const double fx = x - x0, fy = y - y0;
  Bands out(0.0);
  for (int dy = 0; dy <= 1; ++dy)
    for (int dx = 0; dx <= 1; ++dx) {
      const int xi = std::clamp(x0 + dx, 0, images.width - 1), yi = std::clamp(y0 + dy, 0, images.height - 1);
      const double w = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy);
      const size_t texel = size_t(yi) * size_t(images.width) + size_t(xi);
      for (int c = 0; c < 3; ++c) out[c] += w * values[3 * texel + size_t(c)];
    }
  return out;
}

/// The irradiance the solution puts at p on `face` (B̂ − E)/ρ̄, read from its nodes (docs/export.md).
Bands solutionIrradiance(const Scene &scene, const Solution &solution, uint32_t face, const Vec3 &p) {
  const MeshLocation at = solution.mesh.locate(face, p);
  const Bands b = solution.interpolate(solution.nodeRadiosity, at);
  const Bands rho = solution.interpolate(solution.nodeReflectance, at);
  const Bands emitted = scene.materials[scene.faces[face].material].emission * kPi;
  Bands h;
  for (int c = 0; c < 3; ++c) h[c] = std::max(b[c] - emitted[c], 0.0) / rho[c];
  return h;
}

/// False in a piece of the face that the mesh left out (under a block, behind the lamp).
bool visiblePiece(const Solution &solution, uint32_t face, const Vec3 &p) {
  return solution.mesh.patches[size_t(solution.mesh.patchAt(face, p))].depthInside(p) >= 0;
}

/// The range of the solution's irradiance over the points of the face within
/// `radius` of p (a grid of spacing radius/16 in the face's plane).
std::pair<Bands, Bands> solutionRange(const Scene &scene, const Solution &solution,
                                      std::span<const LightmapTriangle> faceTriangles, const Vec3 &p, double radius) {
  const Vec3 n = normalOf(faceTriangles[0]);
  const Vec3 a = normalize(cross(std::abs(n.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0), n)), b = cross(n, a);
  Bands low(INFINITY), high(-INFINITY);
  for (int i = -16; i <= 16; ++i)
    for (int j = -16; j <= 16; ++j) {
      const Vec3 q = p + a * (radius * i / 16) + b * (radius * j / 16);
      bool inside = false;
      for (const LightmapTriangle &t : faceTriangles) {
        const Vec3 e1 = t.corners[1] - t.corners[0], e2 = t.corners[2] - t.corners[0], d = q - t.corners[0];
        const double aa = dot(e1, e1), ab = dot(e1, e2), bb = dot(e2, e2), r1 = dot(d, e1), r2 = dot(d, e2);
        const double det = aa * bb - ab * ab, b1 = (bb * r1 - ab * r2) / det, b2 = (aa * r2 - ab * r1) / det;
        inside |= b1 >= 0 && b2 >= 0 && b1 + b2 <= 1;
      }
      if (!inside || !visiblePiece(solution, faceTriangles[0].face, q)) continue;
      const Bands h = solutionIrradiance(scene, solution, faceTriangles[0].face, q);
      for (int c = 0; c < 3; ++c) low[c] = std::min(low[c], h[c]), high[c] = std::max(high[c], h[c]);
    }
  return {low, high};
}

/// A lookup reads four texels, each the mean of samples within half a texel
/// of its centre, or a dilated texel's covered neighbours one texel further:
/// everything it returns comes from points within 3.5 texels of p along each
/// axis, so it lies within the solution's range over a disc of 3.5·√2 texels.
constexpr double kLookupReachTexels = 3.5 * 1.4142135623730951;

/// A scene's solution baked into an atlas `size` texels a side, with its triangles by face.
struct Baked {
  Baked(Scene sceneIn, double meshSize, int size)
      : scene(std::move(sceneIn)), solution(solveWith(scene, meshSize, 1e-4)) {
    triangles = lightmapTriangles(scene, solution);
    AtlasOptions options;
    options.size = size;
    atlas = buildLightmapAtlas(triangles, options);
    images = bakeLightmap(scene, solution, triangles, atlas);
    for (const LightmapTriangle &t : triangles) byFace[t.face].push_back(t);
  }
  Scene scene;
  Solution solution;
  std::vector<LightmapTriangle> triangles;
  LightmapAtlas atlas;
  LightmapImages images;
  std::map<uint32_t, std::vector<LightmapTriangle>> byFace;
};

/// What a lookup returns lies in the solution's range near the point.
/// Returns how many points were checked on the back faces of two-sided surfaces.
size_t expectLookupsFollowTheSolution(const Baked &baked) {
  const auto &[scene, solution, triangles, atlas, images, byFace] = baked;
  Pcg32 rng(7, 1);
  size_t checked = 0, onBacks = 0;
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int s = 0; s < 40; ++s) {
      double u = rng.next(), v = rng.next();
      if (u + v > 1) u = 1 - u, v = 1 - v;
      const LightmapTriangle &tri = triangles[t];
      const Vec3 p = tri.corners[0] * (1 - u - v) + tri.corners[1] * u + tri.corners[2] * v;
      if (!visiblePiece(solution, tri.face, p)) continue;
      const double *uv = &atlas.texelCoordinates[6 * t];
      const double x = uv[0] * (1 - u - v) + uv[2] * u + uv[4] * v, y = uv[1] * (1 - u - v) + uv[3] * u + uv[5] * v;
      const Bands looked = bilinear(images, images.irradiance, x, y);
      const auto [low, high] =
          solutionRange(scene, solution, byFace.at(tri.face), p, kLookupReachTexels * atlas.texelSize);
      for (int c = 0; c < 3; ++c) {
        const double slack = 1e-5 * high[c];  // float texels
        EXPECT_GE(looked[c], low[c] - slack) << "triangle " << t << " point " << s << " band " << c;
        EXPECT_LE(looked[c], high[c] + slack) << "triangle " << t << " point " << s << " band " << c;
      }
      ++checked;
      onBacks += scene.faces[tri.face].back;
    }
  EXPECT_GT(checked, triangles.size() * 20);
  return onBacks;
}

TEST(LightmapBake, ALookupReturnsTheSolutionNearThePoint) {
  expectLookupsFollowTheSolution(Baked(loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json"), 0.1, 256));
}

// A two-sided panel's back is a face of its own, wound the other way: it
// gets a chart of its own (its normal is the front's turned round), and its
// texels hold the back's light, not the front's.
TEST(LightmapBake, TheBackOfATwoSidedPanelHoldsItsOwnLight) {
  const Baked baked(loadScene(RADIANT_SOURCE_DIR "/scenes/two-sided-panel/scene.json"), 0.1, 256);
  EXPECT_GT(expectLookupsFollowTheSolution(baked), 20u);
  size_t backs = 0;
  for (size_t t = 0; t < baked.triangles.size(); ++t) {
    const Face &face = baked.scene.faces[baked.triangles[t].face];
    if (!face.back) continue;
    ++backs;
    EXPECT_GT(dot(normalOf(baked.triangles[t]), baked.scene.faceNormal(face)), 0.999);
    for (size_t u = 0; u < baked.triangles.size(); ++u) {
      if (baked.triangles[u].face == uint32_t(face.twin)) {
        EXPECT_NE(baked.atlas.chartOfTriangle[t], baked.atlas.chartOfTriangle[u]);
      }
    }
  }
  EXPECT_GT(backs, 0u);
}

/// Across an edge between two charts, the lookups on either side differ no
/// more than the solution does there, plus what it changes within each
/// lookup's reach: dilation must not bleed one chart's light into the other's.
void expectSeamsFollowTheSolution(const Baked &baked) {
  const auto &[scene, solution, triangles, atlas, images, byFace] = baked;
  // Edges by their corners' positions: the triangles on each side.
  std::map<std::array<double, 6>, std::vector<std::pair<uint32_t, int>>> edges;
  for (uint32_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      Vec3 a = triangles[t].corners[k], b = triangles[t].corners[(k + 1) % 3];
      if (std::tie(a.x, a.y, a.z) > std::tie(b.x, b.y, b.z)) std::swap(a, b);
      edges[{a.x, a.y, a.z, b.x, b.y, b.z}].push_back({t, k});
    }
  size_t seams = 0;
  for (const auto &[key, sides] : edges) {
    if (sides.size() != 2 || atlas.chartOfTriangle[sides[0].first] == atlas.chartOfTriangle[sides[1].first]) continue;
    if (dot(normalOf(triangles[sides[0].first]), normalOf(triangles[sides[1].first])) < -0.5) continue;  // two sides
    for (double along : {0.25, 0.5, 0.75}) {
      Bands looked[2], low[2], high[2], here[2];
      bool visible = true;
      for (int side = 0; side < 2; ++side) {
        const auto [t, k] = sides[size_t(side)];
        const LightmapTriangle &tri = triangles[t];
        // The point on the edge, a thousandth of the way towards the opposite corner (inside this side).
        double b[3] = {0, 0, 0};
        b[k] = 1 - along, b[(k + 1) % 3] = along;
        for (double &w : b) w *= 0.999;
        b[(k + 2) % 3] += 0.001;
        const Vec3 p = tri.corners[0] * b[0] + tri.corners[1] * b[1] + tri.corners[2] * b[2];
        visible &= visiblePiece(solution, tri.face, p);
        const double *uv = &atlas.texelCoordinates[6 * t];
        looked[side] = bilinear(images, images.irradiance, uv[0] * b[0] + uv[2] * b[1] + uv[4] * b[2],
                                uv[1] * b[0] + uv[3] * b[1] + uv[5] * b[2]);
        here[side] = solutionIrradiance(scene, solution, tri.face, p);
        std::tie(low[side], high[side]) =
            solutionRange(scene, solution, byFace.at(tri.face), p, kLookupReachTexels * atlas.texelSize);
      }
      if (!visible) continue;
      for (int c = 0; c < 3; ++c) {
        const double allowed = std::abs(here[0][c] - here[1][c]) + (high[0][c] - low[0][c]) + (high[1][c] - low[1][c]) +
                               1e-5 * std::max(high[0][c], high[1][c]);
        ASSERT_LE(std::abs(looked[0][c] - looked[1][c]), allowed) << "band " << c;
      }
      ++seams;
    }
  }
  EXPECT_GT(seams, 10u);
}

TEST(LightmapBake, SeamsAtTheRightAnglesOfABoxFollowTheSolution) {
  expectSeamsFollowTheSolution(Baked(loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json"), 0.1, 256));
}

TEST(LightmapBake, SeamsOnATessellatedSphereFollowTheSolution) {
  expectSeamsFollowTheSolution(Baked(roomWithSphere(16), 0.2, 512));
}

// 8 bits of mantissa on the largest channel: a relative error of at most 2⁻⁸
// of it on every channel, over RGBE's whole range.
TEST(LightmapEncoding, RgbeKeepsEightBitsOfTheLargestChannel) {
  for (const float scale : {1e-20f, 1e-3f, 0.7f, 1.0f, 3.0f, 1e4f, 1e30f}) {
    const float rgb[3] = {scale, 0.37f * scale, 0.0013f * scale};
    const auto back = decodeRgbe(encodeRgbe(rgb));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[size_t(c)], rgb[c], rgb[0] / 256.0) << scale << " band " << c;
  }
  const float black[3] = {0, 0, 0};
  EXPECT_EQ(encodeRgbe(black)[3], 0);
  const float negative[3] = {-1, 0.5f, 0};
  EXPECT_NEAR(decodeRgbe(encodeRgbe(negative))[0], 0.0f, 0.5f / 256);
}

// The file: the faces with TEXCOORD_1, unlit materials whose base colour is
// the display lightmap on TEXCOORD_1, and RADIANT_lightmap with the RGBE
// irradiance and the material's own colour.
TEST(LightmapExport, TheGlbHoldsTheLightmapAsDocumented) {
  const Baked bakedScene(loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json"), 0.1, 128);
  const auto &[scene, solution, triangles, atlas, images, byFace] = bakedScene;
  const BakedMesh baked = lightmapMesh(scene, triangles, atlas, solution.elementCount());
  GltfLightmap lightmap;
  lightmap.displayPng = lightmapDisplayPng(images, test::identityDisplay);
  lightmap.irradiancePng = lightmapIrradiancePng(images);
  lightmap.width = atlas.width, lightmap.height = atlas.height, lightmap.texelSize = atlas.texelSize;
  lightmap.charts = atlas.charts.size();
  test::TempDir dir("lightmap");
  const std::string path = dir.file("cornell.glb");
  writeGltf(scene, baked, ExportProvenance{"gauss-seidel", "linear", {}, ""}, path, &lightmap);

  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, path)) << error;
  size_t triangleCount = 0;
  for (const tinygltf::Primitive &p : model.meshes[0].primitives) {
    ASSERT_TRUE(p.attributes.count("TEXCOORD_1"));
    EXPECT_FALSE(p.attributes.count("COLOR_0"));
    triangleCount += model.accessors[size_t(p.indices)].count / 3;
    const tinygltf::Material &m = model.materials[size_t(p.material)];
    EXPECT_TRUE(m.extensions.count("KHR_materials_unlit"));
    EXPECT_EQ(m.pbrMetallicRoughness.baseColorTexture.texCoord, 1);
    ASSERT_TRUE(m.extensions.count("RADIANT_lightmap"));
    const tinygltf::Value &ext = m.extensions.at("RADIANT_lightmap");
    EXPECT_EQ(ext.Get("encoding").Get<std::string>(), "rgbe");
    EXPECT_EQ(ext.Get("irradianceTexture").Get("texCoord").GetNumberAsInt(), 1);
    // The material's own colour, for engines that light it themselves.
    const tinygltf::Value &factor = ext.Get("baseColorFactor");
    ASSERT_EQ(factor.ArrayLen(), 3u);
    const std::string name = m.name;
    const auto source = std::find_if(scene.materials.begin(), scene.materials.end(),
                                     [&](const Material &material) { return material.name == name; });
    ASSERT_NE(source, scene.materials.end()) << name;
    for (int c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(factor.Get(c).GetNumberAsDouble(), source->diffuse[c]) << name;
  }
  EXPECT_EQ(triangleCount, triangles.size()) << "the scene's own faces, as triangles";

  // The file's own TEXCOORD_1 reads, at each triangle's centre, the solution's light there.
  std::map<std::array<long, 3>, const LightmapTriangle *> byCentre;
  auto key = [](const Vec3 &c) {
    return std::array<long, 3>{std::lround(c.x * 1e5), std::lround(c.y * 1e5), std::lround(c.z * 1e5)};
  };
  for (const LightmapTriangle &t : triangles) byCentre[key((t.corners[0] + t.corners[1] + t.corners[2]) / 3.0)] = &t;
  auto floats = [&](int accessor) {
    const tinygltf::Accessor &a = model.accessors[size_t(accessor)];
    const tinygltf::BufferView &v = model.bufferViews[size_t(a.bufferView)];
    return reinterpret_cast<const float *>(&model.buffers[0].data[v.byteOffset + a.byteOffset]);
  };
  size_t read = 0;
  for (const tinygltf::Primitive &p : model.meshes[0].primitives) {
    const float *positions = floats(p.attributes.at("POSITION")), *uvs = floats(p.attributes.at("TEXCOORD_1"));
    const tinygltf::Accessor &indices = model.accessors[size_t(p.indices)];
    const auto *index = reinterpret_cast<const uint16_t *>(
        &model.buffers[0].data[model.bufferViews[size_t(indices.bufferView)].byteOffset + indices.byteOffset]);
    ASSERT_EQ(indices.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
    for (size_t t = 0; t < indices.count / 3; ++t) {
      Vec3 centre;
      double x = 0, y = 0;
      for (size_t k = 0; k < 3; ++k) {
        const uint16_t i = index[3 * t + k];
        centre += Vec3(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]) / 3.0;
        x += uvs[2 * i] * atlas.width / 3.0, y += uvs[2 * i + 1] * atlas.height / 3.0;
      }
      const auto found = byCentre.find(key(centre));
      ASSERT_NE(found, byCentre.end());
      const LightmapTriangle &tri = *found->second;
      if (!visiblePiece(solution, tri.face, centre)) continue;
      const Bands looked = bilinear(images, images.irradiance, x, y);
      const auto [low, high] =
          solutionRange(scene, solution, byFace.at(tri.face), centre, kLookupReachTexels * atlas.texelSize);
      for (int c = 0; c < 3; ++c) {
        EXPECT_GE(looked[c], low[c] - 1e-5 * high[c]) << "triangle " << t << " band " << c;
        EXPECT_LE(looked[c], high[c] + 1e-5 * high[c]) << "triangle " << t << " band " << c;
      }
      ++read;
    }
  }
  EXPECT_GT(read, triangles.size() / 2);
  ASSERT_EQ(model.images.size(), 2u);
  for (const tinygltf::Image &image : model.images) {
    EXPECT_EQ(image.width, atlas.width);
    EXPECT_EQ(image.height, atlas.height);
  }
  // The RGBE image decodes to the baked irradiance.
  const tinygltf::Image &rgbe = model.images[1];
  ASSERT_EQ(rgbe.component, 4);
  for (size_t i = 0; i < images.irradiance.size() / 3; i += 97) {
    const std::array<uint8_t, 4> texel{rgbe.image[4 * i], rgbe.image[4 * i + 1], rgbe.image[4 * i + 2],
                                       rgbe.image[4 * i + 3]};
    const auto h = decodeRgbe(texel);
    const float largest =
        std::max({images.irradiance[3 * i], images.irradiance[3 * i + 1], images.irradiance[3 * i + 2]});
    for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(h[c], images.irradiance[3 * i + c], largest / 256.0 + 1e-30);
  }
}

}  // namespace
}  // namespace radiant
