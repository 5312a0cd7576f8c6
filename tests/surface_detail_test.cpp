// Texture and bump maps on top of the radiosity solution (C&W §9.4, eq. 9.11;
// Chen & Wu 1990; docs/textures.md), in every renderer.
#include "raytrace/surface_detail.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "io/image.h"
#include "radiosity/solver.h"
#include "render/bump_gather.h"
#include "render/driver.h"
#include "render/registry.h"
#include "render/renderer.h"
#include "render_helpers.h"
#include "sanitizer.h"
#include "scene/load_scene.h"
#include "test_scenes.h"
#include "util/error.h"

namespace radiant {
namespace {

const std::string kTexturedBox = std::string(RADIANT_SOURCE_DIR) + "/scenes/cornell-textured/scene.json";
const std::string kMethods[] = {"path", "flat", "interpolate", "rushmeier", "reichert", "shirley", "kok"};

std::string readText(const std::string &path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

std::string replaced(std::string text, const std::string &from, const std::string &to) {
  size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

/// The textured box's JSON with its materials edited, loaded as if it were
/// the bundled file (so textures/… resolve).
Scene texturedBox(const std::vector<std::pair<std::string, std::string>> &edits = {}) {
  std::string text = readText(kTexturedBox);
  for (const auto &[from, to] : edits) text = replaced(text, from, to);
  return parseSceneJson(text, kTexturedBox);
}

/// Renders with the pixel spread the command line gives (textures filtered), solving first if needed.
Film render(const Scene &scene, const std::string &method, int spp, int size = 32, double meshSize = 0.1) {
  RenderContext options;
  options.pixelSpreadAngle = pixelAngle(scene.camera, size);
  return test::solveAndRender(scene, method, options, spp, size, meshSize);
}

/// The pixels whose centre ray first meets the named object.
std::vector<size_t> pixelsOf(const Scene &scene, const std::string &object, int size) {
  return test::pixelsWhere(scene, size,
                           [&](const Hit &hit) { return scene.objects[scene.faces[hit.face].object].name == object; });
}

struct RegionStats {
  double mean = 0, standardError = 0;  ///< of the region's mean luminance-weighted radiance
  double spatialVariance = 0;          ///< across the region's pixels, per-pixel noise removed
};

RegionStats regionStats(const Film &film, const std::vector<size_t> &pixels) {
  RegionStats s;
  double noise = 0, sumSquares = 0;
  for (size_t p : pixels) {
    double v = film.mean(p).luminance();
    s.mean += v, sumSquares += v * v;
    Bands var = film.varianceOfMean(p);
    noise += 0.2126390 * 0.2126390 * var[0] + 0.7151687 * 0.7151687 * var[1] + 0.0721923 * 0.0721923 * var[2];
  }
  const double n = double(pixels.size());
  s.mean /= n;
  // The bands' noise is correlated (one path per sample): bound it by the sum of σ's, squared.
  s.standardError = 0;
  for (size_t p : pixels) {
    Bands var = film.varianceOfMean(p);
    double sigma = 0.2126390 * std::sqrt(var[0]) + 0.7151687 * std::sqrt(var[1]) + 0.0721923 * std::sqrt(var[2]);
    s.standardError += sigma * sigma;
  }
  s.standardError = std::sqrt(s.standardError) / n;
  s.spatialVariance = sumSquares / n - s.mean * s.mean - noise / n;
  return s;
}

/// The largest per-pixel, per-band difference of two films, relative to the
/// first (dark pixels below 1e-3 compared absolutely).
double worstRelativeDifference(const Film &a, const Film &b) {
  double worst = 0;
  for (size_t p = 0; p < a.pixelCount(); ++p)
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(a.mean(p)[c] - b.mean(p)[c]) / std::max(1e-3, a.mean(p)[c]));
  return worst;
}

// C&W eq. 9.11: a texture whose value everywhere is the untextured
// reflectance changes nothing — in the solution (ρ̄ = ρ) and at every pixel
// (ρ(x)/ρ̄ = 1) — for every method. The texture is stored as float, so the
// images agree to float precision of the reflectance (1e-6 relative).
TEST(SurfaceDetail, AConstantTextureEqualToTheReflectanceChangesNoImage) {
  const auto dir = std::filesystem::temp_directory_path() / ("radiant-detail-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const Bands white(0.885809, 0.698859, 0.666422);
  Image constant(3, 5);  // odd sizes: mip levels average fractional texels
  for (size_t i = 0; i < constant.rgb.size(); ++i) constant.rgb[i] = float(white[int(i % 3)]);
  const std::string texture = (dir / "white.exr").string();
  writeExr(constant, texture);
  Scene plain = loadScene(std::string(RADIANT_SOURCE_DIR) + "/scenes/cornell-box/scene.json");
  Scene textured = texturedBox({{R"("texture": "textures/checker.png")", "\"texture\": \"" + texture + "\""},
                                {R"("bump": "textures/egg-crate.png",)", ""},
                                {R"("bump_scale": 12)", R"("comment": "no bump")"}});
  for (const std::string &method : kMethods) {
    Film a = render(plain, method, 2, 16, 0.15), b = render(textured, method, 2, 16, 0.15);
    const double worst = worstRelativeDifference(a, b);
    EXPECT_LT(worst, 1e-5) << method;
  }
  std::filesystem::remove_all(dir);
}

// By C&W eq. 9.11 the area average of the textured radiosity over an element
// equals the untextured radiosity. flat shows E + (B_e − E)·ρ(x)/ρ̄_e with
// ρ̄_e the exact mean of ρ over the element (Texture::average), so the mean
// of what it shows over the element, sampled on a fine grid, is B_e.
TEST(SurfaceDetail, FlatDisplayKeepsEachElementsMean) {
  Scene scene = texturedBox();
  RayTracer tracer(scene);
  MeshOptions mesh;
  mesh.maxEdgeLength = 0.2;
  SolverOptions solver;
  solver.solver = "gauss-seidel";
  Solution solution = meshAndSolve(scene, tracer, mesh, solver);
  RenderContext options;
  options.solution = &solution;
  auto flat = createRenderer("flat", tracer, options);
  // The floor's elements, each sampled by rays straight down on a 64 × 64 grid of its (parallelogram-like) quad.
  int checked = 0;
  for (uint32_t e = 0; e < solution.elementCount(); ++e) {
    const Element &element = solution.mesh.elements[e];
    if (scene.objects[solution.mesh.patchOf(e).object].name != "floor" || element.vertexCount != 4) continue;
    const Vec3 p0 = solution.mesh.nodes[element.nodes[0]], p1 = solution.mesh.nodes[element.nodes[1]];
    const Vec3 p2 = solution.mesh.nodes[element.nodes[2]], p3 = solution.mesh.nodes[element.nodes[3]];
    double sum = 0;
    const int n = 64;
    Sampler rng{Pcg32()};
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        double s = (i + 0.5) / n, t = (j + 0.5) / n;
        Vec3 p = (p0 * (1 - s) + p1 * s) * (1 - t) + (p3 * (1 - s) + p2 * s) * t;
        sum += flat->radiance(Ray{p + Vec3{0, 0.01, 0}, {0, -1, 0}}, rng).luminance();
      }
    // Grid quadrature of a function with checker edges through the element: O(1/n) error.
    EXPECT_NEAR(sum / (n * n), solution.displayRadiosity(e).luminance() * kInvPi,
                3.0 / n * solution.displayRadiosity(e).luminance() * kInvPi)
        << "element " << e;
    ++checked;
  }
  EXPECT_GT(checked, 4);
}

// A bump map with scale 0, and a flat normal map, change nothing.
TEST(SurfaceDetail, AFlatBumpChangesNoImage) {
  Scene plain =
      texturedBox({{R"("bump": "textures/egg-crate.png",)", ""}, {R"("bump_scale": 12)", R"("comment": "-")"}});
  Scene zero = texturedBox({{R"("bump_scale": 12)", R"("bump_scale": 0)"}});
  for (const std::string &method : kMethods) {
    if (method == "reichert") continue;  // slow, and shades with the same VisiblePoint normal as rushmeier
    Film a = render(plain, method, 2, 16, 0.15), b = render(zero, method, 2, 16, 0.15);
    const double worst = worstRelativeDifference(a, b);
    EXPECT_LT(worst, 1e-9) << method;
  }
}

// Chen's resumming (Chen & Wu, SIGGRAPH 1990): n' = n gives ratio 1 exactly; in
// a furnace (uniform radiance) a tilt θ' keeps the part of its cosine lobe
// above the surface, r = (1 + cos θ')/2, exactly at the gathered tilts (30°,
// 60°) and between them too (the tilt is interpolated in 1 − cos θ', in which r
// is linear); beyond 60° the last level holds.
TEST(SurfaceDetail, BumpGatherKeepsTheLobeAboveTheSurface) {
  Scene scene = test::furnace(1.0, 0.5);
  scene.textures.push_back(Texture(1, 1, {Bands(0.5)}));
  scene.materials[0].bumpTextureIndex = 0;
  RayTracer tracer(scene);
  MeshOptions mesh;
  mesh.maxEdgeLength = 0.5;
  SolverOptions solver;
  solver.solver = "gauss-seidel";
  solver.tolerance = 1e-10;
  Solution solution = meshAndSolve(scene, tracer, mesh, solver);
  BumpGatherOptions options;
  options.rays = 4096;
  BumpGather gather(tracer, solution, options);
  ASSERT_FALSE(gather.empty());
  for (uint32_t v = 0; v < solution.mesh.nodes.size(); v += 5) {
    const Vec3 n = solution.mesh.patches[solution.mesh.nodePatch[v]].normal;
    EXPECT_EQ(gather.nodeRatio(v, n)[1], 1.0);
    const Frame f = Frame::fromNormal(n);
    for (double tilt : {10.0, 30.0, 45.0, 60.0, 80.0}) {
      const double t = tilt * kPi / 180, expected = 0.5 * (1 + std::cos(std::min(t, kPi / 3)));
      // Stratified 64 × 64 directions over a uniform field: the kink of max(0, n'·ω)
      // crosses strata, an O(1/64) quadrature error of the tilted sums (measured below 3e-3).
      EXPECT_NEAR(gather.nodeRatio(v, f.toWorld({std::sin(t) * 0.6, std::sin(t) * 0.8, std::cos(t)}))[1], expected,
                  5e-3)
          << "tilt " << tilt;
    }
  }
}

// The issue's Cornell tests. Every method's bias against path on the
// textured floor (mean over the floor's pixels) stays what it is on the
// untextured floor, within 4σ: the texture adds no error of its own. And on
// the bump-mapped wall shirley and path agree in mean and in the variance of
// shading across the wall (the bumps' light and shade), per-pixel noise removed.
TEST(SurfaceDetail, CornellTexturedFloorAndBumpedWallAgreeWithPath) {
  RADIANT_SKIP_UNDER_SANITIZER();
  const int size = 48;
  Scene textured = texturedBox();
  Scene plain = loadScene(std::string(RADIANT_SOURCE_DIR) + "/scenes/cornell-box/scene.json");
  const std::vector<size_t> floor = pixelsOf(textured, "floor", size), wall = pixelsOf(textured, "back-wall", size);
  ASSERT_GT(floor.size(), 100u);
  ASSERT_GT(wall.size(), 400u);
  const Film pathTextured = render(textured, "path", 512, size), pathPlain = render(plain, "path", 512, size);
  const RegionStats pathFloor = regionStats(pathTextured, floor), pathPlainFloor = regionStats(pathPlain, floor);
  for (const std::string method : {"interpolate", "rushmeier", "shirley", "kok"}) {
    const RegionStats a = regionStats(render(textured, method, 16, size, 0.05), floor);
    const RegionStats b = regionStats(render(plain, method, 16, size, 0.05), floor);
    const double ratioTextured = a.mean / pathFloor.mean, ratioPlain = b.mean / pathPlainFloor.mean;
    const double sigma = std::hypot(a.standardError / a.mean, pathFloor.standardError / pathFloor.mean) +
                         std::hypot(b.standardError / b.mean, pathPlainFloor.standardError / pathPlainFloor.mean);
    EXPECT_NEAR(ratioTextured, ratioPlain, 4 * sigma + 0.005) << method;
    std::cout << method << " floor / path: textured " << ratioTextured << ", untextured " << ratioPlain << "\n";
  }
  const RegionStats pathWall = regionStats(pathTextured, wall), pathPlainWall = regionStats(pathPlain, wall);
  const RegionStats shirleyWall = regionStats(render(textured, "shirley", 64, size, 0.05), wall);
  const RegionStats shirleyPlainWall = regionStats(render(plain, "shirley", 64, size, 0.05), wall);
  const RegionStats chenWall = regionStats(render(textured, "interpolate", 16, size, 0.05), wall);
  // Mean: shirley's bias on the bumped wall is its bias on the flat wall (the solution's), within 4σ.
  const double sigma =
      std::hypot(shirleyWall.standardError / shirleyWall.mean, pathWall.standardError / pathWall.mean) +
      std::hypot(shirleyPlainWall.standardError / shirleyPlainWall.mean,
                 pathPlainWall.standardError / pathPlainWall.mean);
  EXPECT_NEAR(shirleyWall.mean / pathWall.mean, shirleyPlainWall.mean / pathPlainWall.mean, 4 * sigma + 0.005);
  // Variance of shading across the wall: the bumps' light and shade, noise removed. The
  // estimate's own error (a few % at these sample counts) and the solution's smooth
  // indirect light under the bumps (shirley bumps only the direct part) allow 15 %.
  EXPECT_NEAR(shirleyWall.spatialVariance / pathWall.spatialVariance, 1.0, 0.15);
  std::cout << "back wall: shading variance shirley / path " << shirleyWall.spatialVariance / pathWall.spatialVariance
            << ", interpolate (Chen) / path " << chenWall.spatialVariance / pathWall.spatialVariance << "; mean "
            << shirleyWall.mean / pathWall.mean << ", " << chenWall.mean / pathWall.mean << " (flat wall: shirley "
            << shirleyPlainWall.mean / pathPlainWall.mean << ")\n";
}

/// One quad in the plane y = 0 facing +y, with the given corners, texture
/// coordinates and material; the scene's only face.
Scene quadScene(const std::array<Vec3, 4> &corners, const std::array<std::array<double, 2>, 4> &uv, Material m) {
  Scene s;
  s.objects.push_back({"quad", "test"});
  Face f;
  f.vertexCount = 4;
  for (int k = 0; k < 4; ++k) {
    f.vertices[k] = uint32_t(s.positions.size());
    s.positions.push_back(corners[k]);
    f.uvs[k] = int32_t(s.uvs.size() / 2);
    s.uvs.push_back(uv[k][0]), s.uvs.push_back(uv[k][1]);
  }
  s.materials.push_back(m);
  s.addFace(f);
  return s;
}

Hit hitAt(const Scene &scene, const Vec3 &p) {
  RayTracer tracer(scene);
  Hit hit;
  EXPECT_TRUE(tracer.intersect(Ray{p + Vec3{0, 1, 0}, {0, -1, 0}}, hit));
  return hit;
}

// Blinn's bump normal (review): a height ramp h = u over a 1 m square with
// bump_scale s tilts the normal away from the rising side by atan(s): n' =
// (−s, 1, 0)/√(1 + s²) when u runs along +x — and mirrored texture
// coordinates (u along −x) mirror the tilt. A tangent-space normal map of
// (0.75, 0.5, 0.933) is the normal 0.5 along +u and 0.866 out of the surface.
TEST(SurfaceDetail, BumpAndNormalMapsTiltTheNormalTheRightWay) {
  std::vector<Bands> ramp;
  for (int i = 0; i < 64; ++i) ramp.push_back(Bands((i + 0.5) / 64));
  Material bumpy;
  bumpy.name = "bumpy";
  bumpy.bumpScale = 0.05;
  bumpy.bumpTextureIndex = 0;
  const std::array<Vec3, 4> square = {Vec3{0, 0, 0}, Vec3{0, 0, 1}, Vec3{1, 0, 1}, Vec3{1, 0, 0}};
  for (double direction : {1.0, -1.0}) {
    // u along +x (or −x), v along +z: corners (0,0,0) (0,0,1) (1,0,1) (1,0,0) in order.
    const double u0 = direction > 0 ? 0 : 1, u1 = 1 - u0;
    Scene scene = quadScene(square, {{{u0, 0}, {u0, 1}, {u1, 1}, {u1, 0}}}, bumpy);
    scene.textures.push_back(Texture(64, 1, ramp));
    const Vec3 n = surfaceDetail(scene, hitAt(scene, {0.5, 0, 0.5})).shadingNormal;
    const double s = 0.05;  // dh/dx = ±1 per metre × 0.05 m
    EXPECT_NEAR(n.x, -direction * s / std::sqrt(1 + s * s), 1e-9) << "u along " << direction << " x";
    EXPECT_NEAR(n.y, 1 / std::sqrt(1 + s * s), 1e-9);
    EXPECT_NEAR(n.z, 0, 1e-9);
  }
  Material mapped;
  mapped.name = "mapped";
  mapped.normalTextureIndex = 0;
  Scene scene = quadScene(square, {{{0, 0}, {0, 1}, {1, 1}, {1, 0}}}, mapped);
  scene.textures.push_back(Texture(1, 1, {Bands(0.75, 0.5, 0.5 + 0.5 * std::sqrt(0.75))}));
  const Vec3 n = surfaceDetail(scene, hitAt(scene, {0.3, 0, 0.6})).shadingNormal;
  // The map's texels are floats: 1e-7.
  EXPECT_NEAR(n.x, 0.5, 1e-7);
  EXPECT_NEAR(n.y, std::sqrt(0.75), 1e-7);
  EXPECT_NEAR(n.z, 0, 1e-7);
}

// ρ̄ of an element that crosses a quad's diagonal, where the texture map is
// affine on each triangle but not across (review): on a trapezoid with the
// unit square's coordinates and a ramp texture, averageDiffuse equals the
// mean of ρ(x) over the element's surface (dense midpoint sampling, 200²,
// error well below 1e-3).
TEST(SurfaceDetail, ElementMeansFollowTheTextureAcrossTheQuadsDiagonal) {
  std::vector<Bands> ramp;
  for (int i = 0; i < 32; ++i) ramp.push_back(Bands((i + 0.5) / 32 * 0.9));
  Material m;
  m.name = "ramp";
  m.diffuse = Bands(1.0);
  m.diffuseTexture = "ramp";
  m.diffuseTextureIndex = 0;
  m.textureWrap = TextureWrap::Clamp;
  Scene scene = quadScene({Vec3{0, 0, 0}, Vec3{0.25, 0, 1}, Vec3{0.75, 0, 1}, Vec3{1, 0, 0}},
                          {{{0, 0}, {0, 1}, {1, 1}, {1, 0}}}, m);
  scene.textures.push_back(Texture(32, 1, ramp, TextureWrap::Clamp));
  RayTracer tracer(scene);
  // Elements of a 3 × 4 grid over the trapezoid (bilinear in the corners, like the mesher's).
  auto at = [&](double a, double b) {
    const Vec3 p00{0, 0, 0}, p01{0.25, 0, 1}, p11{0.75, 0, 1}, p10{1, 0, 0};
    return (p00 * (1 - b) + p01 * b) * (1 - a) + (p10 * (1 - b) + p11 * b) * a;
  };
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) {
      const std::array<Vec3, 4> element = {at(i / 3.0, j / 4.0), at(i / 3.0, (j + 1) / 4.0),
                                           at((i + 1) / 3.0, (j + 1) / 4.0), at((i + 1) / 3.0, j / 4.0)};
      double sum = 0, area = 0;
      const int n = 200;
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          const double s = i / 3.0 + (a + 0.5) / n / 3, t = j / 4.0 + (b + 0.5) / n / 4;
          const double ds = 1e-4, dt = 1e-4;  // the area of the sample's cell (the map is not affine)
          const double cell = length(cross(at(s + ds, t) - at(s, t), at(s, t + dt) - at(s, t))) / (ds * dt);
          Hit hit;
          ASSERT_TRUE(tracer.intersect(Ray{at(s, t) + Vec3{0, 1, 0}, {0, -1, 0}}, hit));
          sum += surfaceDetail(scene, hit).diffuse[0] * cell, area += cell;
        }
      EXPECT_NEAR(averageDiffuse(scene, 0, element)[0], sum / area, 1e-3) << "element " << i << ", " << j;
    }
}

// The hierarchical solver decides from the material, not the first element,
// whether a patch is textured (review): a texture black on its left half must
// not make the whole floor black under the default solver.
TEST(SurfaceDetail, HierarchicalSolutionsKeepATexturesBrightHalf) {
  const auto dir = std::filesystem::temp_directory_path() / ("radiant-detail-h-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  Image half(8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) half.pixel(x, y)[c] = x < 4 ? 0.0f : 0.8f;
  const std::string texture = (dir / "half.exr").string();
  writeExr(half, texture);
  Scene scene = texturedBox(
      {{R"("texture": "textures/checker.png")", "\"texture\": \"" + texture + "\", \"texture_wrap\": \"clamp\""}});
  RayTracer tracer(scene);
  MeshOptions mesh;
  SolverOptions solver;
  solver.solver = "hierarchical";
  Solution solution = meshAndSolve(scene, tracer, mesh, solver);
  double brightest = 0;
  for (uint32_t e = 0; e < solution.elementCount(); ++e)
    if (scene.objects[solution.mesh.patchOf(e).object].name == "floor")
      brightest = std::max(brightest, solution.reflectance[e][1]);
  EXPECT_GT(brightest, 0.5);  // the bright half's ρ̄ is 0.8 on elements inside it
  std::filesystem::remove_all(dir);
}

TEST(SurfaceDetail, LoaderErrorsNameWhereTheMapWasNamed) {
  const auto dir = std::filesystem::temp_directory_path() / ("radiant-detail-l-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "broken.png") << "not an image";
  auto error = [&](const std::vector<std::pair<std::string, std::string>> &edits) {
    try {
      texturedBox(edits);
    } catch (const InputError &e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string broken = (dir / "broken.png").string();
  std::string message = error({{R"("texture": "textures/checker.png")", "\"texture\": \"" + broken + "\""}});
  EXPECT_NE(message.find("/materials/checker/texture"), std::string::npos) << message;
  EXPECT_NE(message.find("not an image"), std::string::npos) << message;
  message = error({{R"("bump": "textures/egg-crate.png")", "\"bump\": \"" + broken + "\""}});
  EXPECT_NE(message.find("/materials/bumpy-white/bump"), std::string::npos) << message;
  message = error({{R"("bump_scale": 12)", R"("bump_scale": 12, "normal_map": "textures/checker.png")"}});
  EXPECT_NE(message.find("not both"), std::string::npos) << message;
  message = error(
      {{R"("texture": "textures/checker.png")", R"("texture": "textures/checker.png", "texture_wrap": "mirror")"}});
  EXPECT_NE(message.find("texture_wrap"), std::string::npos) << message;
  // Quads take texture coordinates, four pairs.
  message = error({{R"("name": "floor",)", R"("name": "floor", "uv": [[0, 0], [1, 0]],)"}});
  EXPECT_NE(message.find("/objects/0/uv"), std::string::npos) << message;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace radiant
