// radiant export (docs/export.md): the baked mesh's light against closed
// forms and against the solution it came from, and the glTF and PLY files
// read back.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "display/luminance.h"
#include "export/baked_mesh.h"
#include "export/gltf_writer.h"
#include "export/ply_writer.h"
#include "identity_display.h"
#include "radiosity/solution_query.h"
#include "radiosity/solver.h"
#include "raytrace/surface_detail.h"
#include "refined_mesh.h"
#include "scene/load_scene.h"
#include "scene/spectral_scene.h"
#include "temp_dir.h"
#include "test_scenes.h"

namespace radiant {
namespace {

Solution solveWith(const Scene &scene, const std::string &solver, double meshSize, double tolerance) {
  RayTracer tracer(scene);
  MeshOptions meshOptions;
  meshOptions.maxEdgeLength = meshSize;
  Solution s = initialSolution(scene, buildMesh(scene, meshOptions));
  SolverOptions options;
  options.solver = solver;
  options.tolerance = tolerance;
  solveRadiosity(tracer, s, options);
  return s;
}

double triangleArea(const BakedPrimitive &p, size_t t) {
  Vec3 v[3];
  for (int k = 0; k < 3; ++k) {
    const uint32_t i = p.indices[3 * t + k];
    v[k] = Vec3(p.positions[3 * i], p.positions[3 * i + 1], p.positions[3 * i + 2]);
  }
  return 0.5 * length(cross(v[1] - v[0], v[2] - v[0]));
}

// The furnace (every wall emits L_e = 1 and reflects ρ = ½): L = L_e/(1 − ρ) = 2
// W·sr⁻¹·m⁻² at every vertex, and H = (B − E)/ρ = π·2 W·m⁻²; Gauss–Seidel to 1e-9
// leaves an error of that order, so 1e-6 is the round-off of the float attributes.
TEST(Export, TheFurnaceBakesItsClosedFormAtEveryVertex) {
  const Scene scene = test::furnace(1.0, 0.5);
  const Solution solution = solveWith(scene, "gauss-seidel", 0.25, 1e-9);
  const BakedMesh baked = bakeSolution(scene, solution, test::identityDisplay);
  ASSERT_EQ(baked.primitives.size(), 1u);
  const BakedPrimitive &p = baked.primitives[0];
  ASSERT_GT(p.vertexCount(), 0u);
  for (size_t v = 0; v < p.vertexCount(); ++v)
    for (int c = 0; c < 3; ++c) {
      ASSERT_NEAR(p.radiance[3 * v + c], 2.0, 1e-6) << "vertex " << v;
      ASSERT_NEAR(p.irradiance[3 * v + c], 2.0 * kPi, 1e-5) << "vertex " << v;
      // COLOR_0 = T(L)/ρ̄ clamped: T(2) = 1 (clipped), /0.5 = 2, clamped to 1.
      ASSERT_FLOAT_EQ(p.colour[3 * v + c], 1.0f);
    }
}

// The triangles cover exactly the elements (a quad's four triangles around its
// centre, no gaps, no overlaps), per material, with the front side's normal,
// and every node's light is the solution's there.
TEST(Export, TheTrianglesCoverTheElementsAndCarryTheNodesLight) {
  const Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  const Solution solution = solveWith(scene, "gauss-seidel", 0.1, 1e-4);
  const BakedMesh baked = bakeSolution(scene, solution, test::identityDisplay);
  std::vector<double> elementArea(scene.materials.size(), 0.0), bakedArea(scene.materials.size(), 0.0);
  for (const Element &e : solution.mesh.elements) elementArea[solution.mesh.patches[e.patch].material] += e.area;
  size_t triangles = 0;
  for (const BakedPrimitive &p : baked.primitives) {
    for (size_t t = 0; t < p.triangleCount(); ++t) {
      bakedArea[p.material] += triangleArea(p, t);
      // Winding: the triangle's normal is the vertices' (front) normal.
      const uint32_t i0 = p.indices[3 * t], i1 = p.indices[3 * t + 1], i2 = p.indices[3 * t + 2];
      auto at = [&](uint32_t i) { return Vec3(p.positions[3 * i], p.positions[3 * i + 1], p.positions[3 * i + 2]); };
      const Vec3 n = normalize(cross(at(i1) - at(i0), at(i2) - at(i0)));
      const Vec3 stored(p.normals[3 * i0], p.normals[3 * i0 + 1], p.normals[3 * i0 + 2]);
      ASSERT_GT(dot(n, stored), 0.999) << "material " << p.material << " triangle " << t;
    }
    triangles += p.triangleCount();
  }
  for (size_t m = 0; m < scene.materials.size(); ++m)
    EXPECT_NEAR(bakedArea[m], elementArea[m], 1e-6 * elementArea[m]) << scene.materials[m].name;
  size_t quads = 0, tris = 0;
  for (const Element &e : solution.mesh.elements) (e.vertexCount == 4 ? quads : tris)++;
  EXPECT_GE(triangles, 4 * quads + tris);  // more where T-vertices sit on an element's edges

  // Every node's radiance is max(B, E)/π of its node value; ρ̄H + E = B there.
  size_t checked = 0;
  for (const BakedPrimitive &p : baked.primitives)
    for (size_t v = 0; v < p.vertexCount(); ++v) {
      const Vec3 x(p.positions[3 * v], p.positions[3 * v + 1], p.positions[3 * v + 2]);
      const Vec3 normal(p.normals[3 * v], p.normals[3 * v + 1], p.normals[3 * v + 2]);
      for (size_t n = 0; n < solution.mesh.nodes.size(); ++n) {
        // The node at this place on this surface (nodes of neighbouring patches of one plane are pooled).
        const Patch &patch = solution.mesh.patches[solution.mesh.nodePatch[n]];
        if (length(solution.mesh.nodes[n] - x) > 1e-6 || patch.material != p.material ||
            dot(patch.normal, normal) < 0.999)
          continue;
        const Bands &b = solution.nodeRadiosity[n];
        const Bands e = scene.materials[p.material].emission * kPi;
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(p.radiance[3 * v + c], std::max(b[c], e[c]) / kPi, 1e-6 * (1 + b[c]));
          EXPECT_NEAR(e[c] + solution.nodeReflectance[n][c] * p.irradiance[3 * v + c], std::max(b[c], e[c]),
                      1e-5 * (1 + b[c]));
        }
        ++checked;
        break;
      }
      if (checked > 400) break;
    }
  EXPECT_GT(checked, 100u);
}

// A spectral furnace (grey walls, 7 wavelengths in 3 passes, each solved on a
// mesh of its own size): the passes read at the first pass's vertices and
// combined give radiance of luminance 2 (the grey spectrum 2 has Y = 2 with the
// luminance weights' normalisation) and irradiance of luminance 2π everywhere.
TEST(Export, SpectralPassesCombineAtTheFirstPassesVertices) {
  Scene scene = test::furnace(1.0, 0.5);
  scene.spectral.wavelengths = {400, 450, 500, 550, 600, 650, 700};
  ASSERT_EQ(scene.spectral.passCount(), 3);
  std::vector<BakedMesh> passes;
  for (int pass = 0; pass < 3; ++pass) {
    applySpectralPass(scene, pass);
    const Solution solution = solveWith(scene, "gauss-seidel", 0.5 / (pass + 1), 1e-9);
    passes.push_back(pass == 0 ? bakeSolution(scene, solution) : resampleLight(passes[0], scene, solution));
  }
  applySpectralColour(scene, WhiteBalance::None);
  const BakedMesh rgb = combineSpectralPasses(passes, scene, WhiteBalance::None);
  const BakedPrimitive &p = rgb.primitives[0];
  ASSERT_EQ(p.vertexCount(), passes[0].primitives[0].vertexCount());
  for (size_t v = 0; v < p.vertexCount(); ++v) {
    EXPECT_NEAR(relativeLuminance(&p.radiance[3 * v]), 2.0, 1e-4) << "vertex " << v;
    EXPECT_NEAR(relativeLuminance(&p.irradiance[3 * v]), 2.0 * kPi, 1e-3) << "vertex " << v;
  }
}

// A refined mesh has T-vertices: nodes of small elements inside the edge of a
// large neighbour. The large element's triangles must pass through them, or
// the small ones' leave pinholes along the edge (seen in the viewer as dark
// and bright dots). No edge used by one triangle only may have a vertex at
// its midpoint, where the refinement puts T-vertices.
TEST(Export, RefinedMeshesHaveNoCracksAtTheirTVertices) {
  const Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  // Neighbours two levels apart: T-vertices on T-vertices' edges.
  RadiosityMesh mesh = test::refinedTreeMesh(scene, 0.2);
  ASSERT_FALSE(mesh.tVertices.empty());
  Solution solution = initialSolution(scene, std::move(mesh));
  solution.radiosity = solution.emission;
  solution.updateNodesAndErrors();
  const BakedMesh baked = bakeSolution(scene, solution, test::identityDisplay);
  size_t openEdges = 0;
  for (const BakedPrimitive &p : baked.primitives) {
    // A vertex by position and normal: the floor's edge is not the back wall's.
    using Key = std::array<float, 6>;
    auto at = [&](uint32_t i) {
      return Key{p.positions[3 * i], p.positions[3 * i + 1], p.positions[3 * i + 2],
                 p.normals[3 * i],   p.normals[3 * i + 1],   p.normals[3 * i + 2]};
    };
    std::set<Key> positions;
    for (size_t v = 0; v < p.vertexCount(); ++v) positions.insert(at(uint32_t(v)));
    std::map<std::pair<Key, Key>, int> uses;
    for (size_t t = 0; t < p.triangleCount(); ++t)
      for (int k = 0; k < 3; ++k) {
        auto a = at(p.indices[3 * t + k]), b = at(p.indices[3 * t + (k + 1) % 3]);
        ++uses[{std::min(a, b), std::max(a, b)}];
      }
    for (const auto &[edge, count] : uses) {
      if (count != 1) continue;
      ++openEdges;
      Key middle = edge.first;
      for (int c = 0; c < 3; ++c) middle[size_t(c)] = 0.5f * (edge.first[size_t(c)] + edge.second[size_t(c)]);
      EXPECT_FALSE(positions.count(middle)) << "a crack at (" << middle[0] << ", " << middle[1] << ", " << middle[2]
                                            << ") in " << scene.materials[p.material].name;
    }
  }
  EXPECT_GT(openEdges, 0u);  // the surfaces' own boundaries
}

// A textured surface carries its texture coordinates (the material's, scale
// applied) at every vertex: the renderer's own parameterisation there.
TEST(Export, TexturedSurfacesKeepTheirTextureCoordinates) {
  const Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-textured/scene.json");
  const Solution solution = solveWith(scene, "gauss-seidel", 0.1, 1e-3);
  const BakedMesh baked = bakeSolution(scene, solution, test::identityDisplay);
  RayTracer tracer(scene);
  size_t textured = 0;
  for (const BakedPrimitive &p : baked.primitives) {
    EXPECT_EQ(p.hasUv, scene.materials[p.material].diffuseTextureIndex >= 0);
    if (!p.hasUv) continue;
    ASSERT_EQ(p.uvs.size(), 2 * p.vertexCount());
    for (size_t v = 0; v < p.vertexCount(); ++v) {
      // Trace to the vertex from just in front of it, and compare with the hit's parameterisation.
      const Vec3 x(p.positions[3 * v], p.positions[3 * v + 1], p.positions[3 * v + 2]);
      const Vec3 n(p.normals[3 * v], p.normals[3 * v + 1], p.normals[3 * v + 2]);
      Hit hit;
      // Vertices on a face's edge are left out: the ray may find the neighbouring face there.
      if (!tracer.intersect(Ray{x + n * 1e-3, n * -1.0}, hit, 2e-3) ||
          std::min({hit.b1, hit.b2, 1 - hit.b1 - hit.b2}) < 1e-3)
        continue;
      const SurfaceParameterisation s = surfaceParameterisation(scene, scene.triangles[hit.triangle], hit.b1, hit.b2);
      EXPECT_NEAR(p.uvs[2 * v], s.u, 1e-4);
      EXPECT_NEAR(p.uvs[2 * v + 1], s.v, 1e-4);
      ++textured;
    }
  }
  EXPECT_GT(textured, 20u);
}

tinygltf::Model readGltf(const std::string &path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  const bool ok = path.ends_with(".glb") ? loader.LoadBinaryFromFile(&model, &error, &warning, path)
                                         : loader.LoadASCIIFromFile(&model, &error, &warning, path);
  EXPECT_TRUE(ok) << error;
  return model;
}

const float *attribute(const tinygltf::Model &model, const tinygltf::Primitive &p, const std::string &name,
                       size_t &count) {
  const tinygltf::Accessor &a = model.accessors[size_t(p.attributes.at(name))];
  const tinygltf::BufferView &view = model.bufferViews[size_t(a.bufferView)];
  count = a.count;
  return reinterpret_cast<const float *>(model.buffers[size_t(view.buffer)].data.data() + view.byteOffset +
                                         a.byteOffset);
}

// The file read back by tinygltf holds what was baked: attributes, the
// camera (its −Z the view direction, +Y up), emitters' L_e as factor ×
// strength, the material in extras.radiant; .glb and .gltf alike.
TEST(Export, TheGltfFileReadsBackAsBaked) {
  const Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  const Solution solution = solveWith(scene, "gauss-seidel", 0.15, 1e-3);
  const BakedMesh baked = bakeSolution(scene, solution, test::identityDisplay);
  for (const std::string extension : {".glb", ".gltf"}) {
    const test::TempDir scratch("export");
    const std::string path = scratch.file("box" + extension);
    writeGltf(scene, baked, ExportProvenance{"gauss-seidel", "linear", {{"exposure", 0.0}}, "linear"}, path);
    const tinygltf::Model model = readGltf(path);
    ASSERT_EQ(model.meshes.size(), 1u);
    ASSERT_EQ(model.meshes[0].primitives.size(), baked.primitives.size());
    for (size_t i = 0; i < baked.primitives.size(); ++i) {
      const BakedPrimitive &b = baked.primitives[i];
      const tinygltf::Primitive &p = model.meshes[0].primitives[i];
      size_t count = 0;
      const float *radiance = attribute(model, p, "_RADIANCE", count);
      ASSERT_EQ(count, b.vertexCount());
      for (size_t k = 0; k < 3 * count; ++k) ASSERT_EQ(radiance[k], b.radiance[k]);
      const float *irradiance = attribute(model, p, "_IRRADIANCE", count);
      for (size_t k = 0; k < 3 * count; ++k) ASSERT_EQ(irradiance[k], b.irradiance[k]);
      EXPECT_EQ(model.accessors[size_t(p.indices)].count, b.indices.size());
      const tinygltf::Material &m = model.materials[size_t(p.material)];
      const Material &original = scene.materials[b.material];
      EXPECT_EQ(m.name, original.name);
      for (int c = 0; c < 3; ++c)
        EXPECT_DOUBLE_EQ(m.pbrMetallicRoughness.baseColorFactor[size_t(c)], original.diffuse[c]);
      EXPECT_NE(m.extensions.count("KHR_materials_unlit"), m.extensions.count("KHR_materials_emissive_strength"));
      const double strength =
          m.extensions.count("KHR_materials_emissive_strength")
              ? m.extensions.at("KHR_materials_emissive_strength").Get("emissiveStrength").GetNumberAsDouble()
              : 1.0;
      for (int c = 0; c < 3; ++c) {
        const double factor = m.emissiveFactor.empty() ? 0.0 : m.emissiveFactor[size_t(c)];
        EXPECT_NEAR(factor * strength, original.emission[c], 1e-9 * (1 + original.emission[c]));
        EXPECT_DOUBLE_EQ(m.extras.Get("radiant").Get("emission").Get(c).GetNumberAsDouble(), original.emission[c]);
      }
      EXPECT_EQ(m.extras.Get("radiant").Get("kind").Get<std::string>(), materialKindName(original.kind));
    }
    // The camera node: translation the eye, rotation taking −Z to the view direction and +Y to up.
    ASSERT_EQ(model.cameras.size(), 1u);
    EXPECT_NEAR(model.cameras[0].perspective.yfov, scene.camera.verticalFovDegrees * kPi / 180, 1e-12);
    const tinygltf::Node &node = model.nodes[1];
    ASSERT_EQ(node.camera, 0);
    const double x = node.rotation[0], y = node.rotation[1], z = node.rotation[2], w = node.rotation[3];
    auto rotate = [&](Vec3 v) {  // q v q*
      const Vec3 u(x, y, z);
      return u * (2 * dot(u, v)) + v * (w * w - dot(u, u)) + cross(u, v) * (2 * w);
    };
    const Vec3 forward = normalize(scene.camera.target - scene.camera.eye);
    EXPECT_GT(dot(rotate(Vec3(0, 0, -1)), forward), 1 - 1e-9);
    EXPECT_GT(dot(rotate(Vec3(0, 1, 0)), normalize(scene.camera.up)), 0.999);
    EXPECT_NEAR(node.translation[0], scene.camera.eye.x, 1e-12);
    EXPECT_EQ(model.asset.extras.Get("radiant").Get("elements").GetNumberAsInt(), int(baked.elements));
  }
}

// The PLY file: its header's counts, and exactly as many bytes as they say.
TEST(Export, ThePlyFileHoldsWhatItsHeaderSays) {
  const Scene scene = test::furnace(1.0, 0.5);
  const Solution solution = solveWith(scene, "gauss-seidel", 0.5, 1e-6);
  const BakedMesh baked = bakeSolution(scene, solution, test::identityDisplay);
  const test::TempDir scratch("export");
  const std::string path = scratch.file("furnace.ply");
  writePly(baked, test::identityDisplay, path);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t headerEnd = bytes.find("end_header\n");
  ASSERT_NE(headerEnd, std::string::npos);
  const size_t vertices = baked.primitives[0].vertexCount(), triangles = baked.primitives[0].triangleCount();
  EXPECT_NE(bytes.find("element vertex " + std::to_string(vertices) + "\n"), std::string::npos);
  EXPECT_NE(bytes.find("element face " + std::to_string(triangles) + "\n"), std::string::npos);
  // x y z nx ny nz (floats), r g b (bytes), 6 floats of light; a face is a count byte and 3 uints.
  EXPECT_EQ(bytes.size(), headerEnd + 11 + vertices * (6 * 4 + 3 + 6 * 4) + triangles * 13);
  // The first vertex: L = 2 → display 1 → red 255, radiance_r = 2.
  const char *first = bytes.data() + headerEnd + 11;
  EXPECT_EQ(uint8_t(first[24]), 255);
  float radiance = 0;
  std::memcpy(&radiance, first + 27, 4);
  EXPECT_NEAR(radiance, 2.0f, 1e-5);
}

}  // namespace
}  // namespace radiant
