// Embree hits against analytic ray–quad answers, and one-sided emission.
#include "raytrace/ray_tracer.h"

#include <gtest/gtest.h>

#include "util/random.h"

namespace radiant {
namespace {

/// A unit square in the plane z = 0 from (0,0) to (1,1), front facing +z, and
/// a second square at z = 2 facing −z.
Scene twoSquares() {
  Scene s;
  s.materials.push_back(Material{});
  s.objects.push_back({"squares", "test"});
  s.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 2}, {0, 1, 2}, {1, 1, 2}, {1, 0, 2}};
  Face a;
  a.vertexCount = 4;
  for (int i = 0; i < 4; ++i) a.vertices[i] = i;
  Face b = a;
  for (int i = 0; i < 4; ++i) b.vertices[i] = 4 + i;
  s.addFace(a);
  s.addFace(b);
  return s;
}

TEST(RayTracer, HitsMatchAnalyticRayPlaneIntersection) {
  Scene scene = twoSquares();
  RayTracer tracer(scene);
  Pcg32 rng(7, 1);
  int hits = 0, misses = 0;
  for (int i = 0; i < 2000; ++i) {
    Vec3 origin{rng.next() * 3 - 1, rng.next() * 3 - 1, 0.5 + rng.next()};
    Vec3 direction = normalize(Vec3{rng.next() - 0.5, rng.next() - 0.5, -1});
    // Analytic: the plane z = 0 at t = −o.z/d.z; inside the square or not.
    double t = -origin.z / direction.z;
    Vec3 p = origin + direction * t;
    bool inside = p.x > 0 && p.x < 1 && p.y > 0 && p.y < 1;
    bool nearEdge = std::min({std::abs(p.x), std::abs(p.x - 1), std::abs(p.y), std::abs(p.y - 1)}) < 1e-5;
    if (nearEdge) continue;
    Hit hit;
    bool found = tracer.intersect({origin, direction}, hit);
    ASSERT_EQ(found, inside) << "ray " << i;
    if (!found) {
      ++misses;
      continue;
    }
    ++hits;
    EXPECT_NEAR(hit.distance, t, 1e-6);
    EXPECT_NEAR(hit.position.x, p.x, 1e-6);
    EXPECT_NEAR(hit.position.y, p.y, 1e-6);
    EXPECT_NEAR(hit.position.z, 0.0, 1e-12);
    EXPECT_NEAR(hit.geometricNormal.z, 1.0, 1e-12);  // counter-clockwise seen from +z
    EXPECT_EQ(scene.triangles[hit.triangle].face, 0u);
  }
  EXPECT_GT(hits, 100);
  EXPECT_GT(misses, 100);
}

TEST(RayTracer, ClosestHitAndOcclusionSegments) {
  Scene scene = twoSquares();
  RayTracer tracer(scene);
  Hit hit;
  // From between the squares, upwards: the square at z = 2, whose front faces −z.
  ASSERT_TRUE(tracer.intersect({{0.3, 0.6, 1}, {0, 0, 1}}, hit));
  EXPECT_NEAR(hit.distance, 1.0, 1e-6);
  EXPECT_NEAR(hit.geometricNormal.z, -1.0, 1e-12);
  EXPECT_EQ(scene.triangles[hit.triangle].face, 1u);
  // Occlusion honours the segment length.
  EXPECT_TRUE(tracer.occluded({{0.3, 0.6, 1}, {0, 0, 1}}, 1.5));
  EXPECT_FALSE(tracer.occluded({{0.3, 0.6, 1}, {0, 0, 1}}, 0.9));
  EXPECT_FALSE(tracer.occluded({{2.3, 0.6, 1}, {0, 0, 1}}, 10));
  // Two points on facing surfaces see each other; a point behind a square does not.
  EXPECT_TRUE(tracer.visible({0.5, 0.5, 0}, {0, 0, 1}, {0.5, 0.5, 2}, {0, 0, -1}));
  EXPECT_FALSE(tracer.visible({0.5, 0.5, -1}, {0, 0, 1}, {0.5, 0.5, 1}, {0, 0, 1}));
}

TEST(RayTracer, StreamQueriesAgreeWithSingleRays) {
  Scene scene = twoSquares();
  RayTracer tracer(scene);
  Pcg32 rng(3, 5);
  std::vector<Ray> rays;
  for (int i = 0; i < 1000; ++i)
    rays.push_back(
        {{rng.next(), rng.next(), 1}, normalize(Vec3{rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5})});
  std::vector<Hit> hits(rays.size());
  std::vector<uint8_t> found(rays.size());
  tracer.intersectMany(rays, hits, found);
  std::vector<HitRecord> records(rays.size());
  tracer.intersectMany(rays, records);
  for (size_t i = 0; i < rays.size(); ++i) {
    Hit single;
    ASSERT_EQ(bool(found[i]), tracer.intersect(rays[i], single));
    ASSERT_EQ(records[i].found(), bool(found[i]));
    if (found[i]) {
      EXPECT_EQ(hits[i].triangle, single.triangle);
      EXPECT_DOUBLE_EQ(hits[i].distance, single.distance);
      Hit completed;
      tracer.completeHit(rays[i], records[i], completed);
      EXPECT_EQ(completed.triangle, single.triangle);
      EXPECT_DOUBLE_EQ(completed.position.x, single.position.x);
    }
  }
}

TEST(RayTracer, DegenerateFacesAreDroppedAndCounted) {
  Scene scene;
  scene.materials.push_back(Material{});
  scene.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}};
  Face line;  // three collinear points
  line.vertices[0] = 0;
  line.vertices[1] = 1;
  line.vertices[2] = 2;
  Face good;
  good.vertices[0] = 0;
  good.vertices[1] = 1;
  good.vertices[2] = 3;
  EXPECT_FALSE(scene.addFace(line));
  EXPECT_TRUE(scene.addFace(good));
  EXPECT_EQ(scene.droppedDegenerateFaces, 1u);
  EXPECT_EQ(scene.triangles.size(), 1u);
}

}  // namespace
}  // namespace radiant
