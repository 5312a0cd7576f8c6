// Smooth surfaces stay smooth (RadiosityMesh::nodeShadingNormals,
// Solution::nodePools): where a model gives vertex normals, the nodes of
// neighbouring facets that share a vertex's normal share one value, so the
// radiosity display has no seam there, although the facets meet at 15°;
// creases (no shared normal) keep their jump. Scenes: the side of a
// 24-segment cylinder (facets 15° apart), with its radial vertex normals,
// without them, and with a flat normal per facet.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "io/solution_file.h"
#include "mesh/mesh.h"
#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"
#include "solution_file_checks.h"

namespace radiant {
namespace {

constexpr int kSegments = 24;  // facets 15° apart
constexpr double kRadius = 0.5, kHeight = 1.0;

enum class Normals { Radial, None, FlatPerFacet };

/// Facets [first, first + count) of the side of a cylinder about the y axis
/// (facet i spans angles 15°·i to 15°·(i + 1)), facing outwards, grey
/// (ρ = 0.5, material 0); with `light`, a 0.5 m square emitter (material 1)
/// at x = 2 facing the cylinder.
Scene cylinder(Normals normals, int first = 0, int count = kSegments, bool light = false) {
  Scene s;
  s.objects.push_back({"cylinder", "test"});
  Material grey;
  grey.diffuse = Bands(0.5);
  Material lamp;
  lamp.diffuse = Bands(0.0);
  lamp.emission = Bands(10.0);
  s.materials = {grey, lamp};
  auto angle = [](int i) { return 2 * kPi * i / kSegments; };
  for (int i = 0; i <= kSegments; ++i) {
    const double c = std::cos(angle(i)), z = std::sin(angle(i));
    s.positions.push_back({kRadius * c, 0, kRadius * z});
    s.positions.push_back({kRadius * c, kHeight, kRadius * z});
    s.normals.push_back({c, 0, z});  // normal i: radial at vertex column i
  }
  for (int i = first; i < first + count; ++i) {
    Face f;
    f.vertexCount = 4;
    f.material = 0;
    // bottom i, top i, top i+1, bottom i+1: counter-clockwise seen from outside.
    const uint32_t b0 = 2 * i, t0 = 2 * i + 1, t1 = 2 * i + 3, b1 = 2 * i + 2;
    f.vertices[0] = b0, f.vertices[1] = t0, f.vertices[2] = t1, f.vertices[3] = b1;
    if (normals == Normals::Radial) {
      f.normals[0] = f.normals[1] = i;
      f.normals[2] = f.normals[3] = i + 1;
    } else if (normals == Normals::FlatPerFacet) {
      const double mid = (angle(i) + angle(i + 1)) / 2;
      s.normals.push_back({std::cos(mid), 0, std::sin(mid)});
      for (int k = 0; k < 4; ++k) f.normals[k] = int32_t(s.normals.size() - 1);
    }
    EXPECT_TRUE(s.addFace(f));
  }
  if (light) {
    const Vec3 corners[4] = {{2, 0.25, -0.25}, {2, 0.25, 0.25}, {2, 0.75, 0.25}, {2, 0.75, -0.25}};  // facing −x
    Face f;
    f.vertexCount = 4;
    f.material = 1;
    for (int k = 0; k < 4; ++k) {
      f.vertices[k] = uint32_t(s.positions.size());
      s.positions.push_back(corners[k]);
    }
    EXPECT_TRUE(s.addFace(f));
  }
  return s;
}

size_t pooledNodes(const std::vector<uint32_t> &pools) {
  size_t count = 0;
  for (uint32_t v = 0; v < pools.size(); ++v) count += pools[v] != v;
  return count;
}

Solution meshed(const Scene &scene) {
  MeshOptions options;
  options.maxEdgeLength = 0.5;  // facets 0.13 × 1 m: 1 × 2 elements, nodes at y = 0, 0.5, 1
  return initialSolution(scene, buildMesh(scene, options));
}

TEST(SmoothNormals, NodesInterpolateTheFacesVertexNormals) {
  const Scene scene = cylinder(Normals::Radial, 0, 3);
  const Solution s = meshed(scene);
  ASSERT_EQ(s.mesh.nodeShadingNormals.size(), s.mesh.nodes.size());
  for (uint32_t v = 0; v < s.mesh.nodes.size(); ++v) {
    // The radial direction at the node's angle: at a face corner the vertex
    // normal, along a vertical edge the same, and (the facets being flat)
    // in between the normalised linear blend of the two columns' normals.
    const Vec3 &p = s.mesh.nodes[v];
    const Patch &patch = s.mesh.patches[s.mesh.nodePatch[v]];
    const Vec3 a = scene.normals[scene.faces[patch.face].normals[0]],
               b = scene.normals[scene.faces[patch.face].normals[2]];
    const Vec3 edge =
        scene.positions[scene.faces[patch.face].vertices[3]] - scene.positions[scene.faces[patch.face].vertices[0]];
    const double t = dot(p - scene.positions[scene.faces[patch.face].vertices[0]], edge) / dot(edge, edge);
    const Vec3 expected = normalize(a * (1 - t) + b * t);
    const ShadingNormal &n = s.mesh.nodeShadingNormals[v];
    // Stored as f32: within 2⁻²⁴ per component, and the double arithmetic before far below.
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(n[k], expected[k], 1e-7) << "node " << v;
  }
}

TEST(SmoothNormals, FacetsSharingVertexNormalsPoolTheirCoincidentNodes) {
  // Four facets, three shared edges of three nodes each (y = 0, 0.5, 1):
  // nine nodes pooled with their neighbour's, although the facets' own
  // normals are 15° apart (the 2° rule alone pools none).
  const Solution s = meshed(cylinder(Normals::Radial, 0, 4));
  EXPECT_EQ(pooledNodes(s.nodePools()), 9u);
}

TEST(SmoothNormals, WithoutVertexNormalsTheFacetsKeepTheirJumps) {
  const Solution s = meshed(cylinder(Normals::None, 0, 4));
  EXPECT_TRUE(s.mesh.nodeShadingNormals.empty());  // nothing stored for a scene without them
  EXPECT_TRUE(s.mesh.patchCornerNormals.empty());
  EXPECT_EQ(pooledNodes(s.nodePools()), 0u);
}

TEST(SmoothNormals, ACreaseKeepsItsJump) {
  // Each facet its own flat normal (different normal indices at the shared
  // vertices, 15° apart): a crease, as a hard-edged model exports it.
  const Solution s = meshed(cylinder(Normals::FlatPerFacet, 0, 4));
  EXPECT_EQ(s.mesh.nodeShadingNormals.size(), s.mesh.nodes.size());
  EXPECT_EQ(pooledNodes(s.nodePools()), 0u);
}

/// The interpolated display radiosity (band 0) at `p` seen from face `face`.
double displayedAt(const Solution &s, uint32_t face, const Vec3 &p) {
  return s.interpolatedRadiosity(s.mesh.locate(face, p))[0];
}

/// The largest jump of the displayed radiosity across the cylinder's shared
/// edges (between face f and f + 1), relative to the cylinder's largest node
/// radiosity, at heights that fall between the nodes of any refinement.
double largestJumpAcrossEdges(const Solution &s, const Scene &scene) {
  double largest = 0, jump = 0;
  for (uint32_t v = 0; v < s.mesh.nodes.size(); ++v)
    if (s.mesh.patches[s.mesh.nodePatch[v]].material == 0) largest = std::max(largest, s.nodeRadiosity[v][0]);
  for (uint32_t f = 0; f + 1 < kSegments; ++f) {
    const Vec3 bottom = scene.positions[scene.faces[f].vertices[3]], top = scene.positions[scene.faces[f].vertices[2]];
    for (double y : {0.0, 0.1, 0.37, 0.5, 0.61, 0.83, 1.0}) {
      const Vec3 p = bottom + (top - bottom) * y;
      jump = std::max(jump, std::abs(displayedAt(s, f, p) - displayedAt(s, f + 1, p)));
    }
  }
  return jump / largest;
}

/// `solver`'s solution of `scene` on a mesh of 0.25 m elements.
Solution solveOnQuarterMetres(const Scene &scene, const RayTracer &tracer, const char *solver, double tolerance) {
  MeshOptions mesh;
  mesh.maxEdgeLength = 0.25;
  SolverOptions options;
  options.solver = solver;
  options.tolerance = tolerance;
  return meshAndSolve(scene, tracer, mesh, options);
}

TEST(SmoothNormals, TheRadiosityIsContinuousAcrossSmoothEdges) {
  // A 24-segment cylinder lit from the side, solved by both solvers that
  // compute the light at the nodes. Seen from either facet, the display at
  // a point of their shared edge interpolates the same node values with
  // weights that differ only by round-off: the nodes of a pool are given
  // one value (copies, not recomputations), and a T-vertex of a finer facet
  // its coarser neighbour's edge interpolation. The weights come from
  // inverting each facet's map in double at coordinates of order 1 m, so
  // they err by a few 10⁻¹⁶; 10⁻¹² of the largest value is that with a wide
  // margin, and far below any jump a seam would make.
  // Without the vertex normals the same solves jump by far more than this:
  // facets 15° apart receive the light at cosines that differ by up to
  // cos 60° − cos 75° ≈ 0.24, which the control below checks (above 5 %).
  for (const char *solver : {"stochastic", "hierarchical-exact"}) {
    SCOPED_TRACE(solver);
    for (Normals normals : {Normals::Radial, Normals::None}) {
      const Scene scene = cylinder(normals, 0, kSegments, true);
      const RayTracer tracer(scene);
      const Solution s = solveOnQuarterMetres(scene, tracer, solver, 1e-3);
      const double jump = largestJumpAcrossEdges(s, scene);
      if (normals == Normals::Radial) {
        EXPECT_LE(jump, 1e-12);
        // Every node of a pool shows its one value, bit for bit.
        const std::vector<uint32_t> pools = s.nodePools();
        EXPECT_GT(pooledNodes(pools), 0u);
        for (uint32_t v = 0; v < pools.size(); ++v)
          EXPECT_EQ(s.nodeRadiosity[v][0], s.nodeRadiosity[pools[v]][0]) << "node " << v;
      } else {
        EXPECT_GT(jump, 0.05);
      }
    }
  }
}

TEST(SmoothNormals, TheSolutionFileKeepsThePools) {
  // The reader derives the shading normals from the scene as the builder did
  // (solution_file_checks.h compares them and the pools), so the node
  // irradiance stored once per pool spreads back over the same pools.
  const Scene scene = cylinder(Normals::Radial, 0, kSegments, true);
  const RayTracer tracer(scene);
  for (const char *solver : {"stochastic", "hierarchical-exact"}) {
    SCOPED_TRACE(solver);
    const Solution s = solveOnQuarterMetres(scene, tracer, solver, 1e-2);
    ASSERT_GT(pooledNodes(s.nodePools()), 0u);
    const std::string path = (std::filesystem::temp_directory_path() / "radiant-smooth-normals-test.rad").string();
    writeSolution(s, scene, path);
    const Solution back = readSolution(path, scene);
    std::filesystem::remove(path);
    test::expectSolutionReadBack(s, back);
  }
}

}  // namespace
}  // namespace radiant
