#include "export/lightmap_bake.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "export/baked_mesh.h"
#include "raytrace/ray_tracer.h"
#include "raytrace/surface_detail.h"
#include "util/phase.h"

namespace radiant {

namespace {

/// The solution read at a point of a lightmap triangle, as `interpolate` reads it.
class SolutionReader {
 public:
  SolutionReader(const Scene &scene, const Solution &solution)
      : scene_(scene), solution_(solution), nodeIrradiance_(nodeIrradiance(solution)) {}

  /// False where p lies in a piece of its face that the mesh left out (hidden
  /// where another surface meets the face, mesh/face_split.h): no light is
  /// read there, and dilation fills such texels from the visible ones.
  bool visible(uint32_t face, const Vec3 &p) const {
    const Patch &patch = solution_.mesh.patches[size_t(solution_.mesh.patchAt(face, p))];
    return patch.depthInside(p) >= -1e-9 * std::sqrt(patch.area);
  }

  /// `b` are p's barycentrics in the lightmap triangle (corners 0, 1, 2).
  SurfaceLight read(const LightmapTriangle &t, const Vec3 &p, const double b[3]) const {
    const Material &material = scene_.materials[scene_.faces[t.face].material];
    SurfaceLight light =
        surfaceLightAt(solution_, nodeIrradiance_, solution_.mesh.locate(t.face, p), material.emission * kPi);
    if (material.diffuseTextureIndex < 0) return light;
    // C&W eq. 9.11: the reflected part E + ρ̄H becomes E + ρ(x)H with the texture there.
    Hit hit;
    hit.triangle = t.triangle;
    hit.b1 = b[1];
    hit.b2 = b[2];
    hit.material = scene_.faces[t.face].material;
    hit.face = t.face;
    hit.position = p;
    const Bands rho = surfaceDetail(scene_, hit).diffuse;
    for (int c = 0; c < kBandCount; ++c)
      if (light.reflectance[c] > kSmallestReflectance)
        light.radiance[c] += light.irradiance[c] * (rho[c] - light.reflectance[c]) * kInvPi;
    return light;
  }

 private:
  const Scene &scene_;
  const Solution &solution_;
  std::vector<Bands> nodeIrradiance_;
};

/// Fills the texels of one chart: each sample point inside one of its triangles reads the solution.
void bakeChart(const LightmapChart &chart, std::span<const LightmapTriangle> triangles, const LightmapAtlas &atlas,
               const SolutionReader &reader, int samples, LightmapImages &out) {
  const int width = chart.width, height = chart.height;
  std::vector<double> sums(size_t(width) * size_t(height) * 6, 0.0);
  std::vector<int> counts(size_t(width) * size_t(height), 0);
  for (uint32_t t : chart.triangles) {
    const double *uv = &atlas.texelCoordinates[6 * size_t(t)];
    const double x0 = uv[0], y0 = uv[1], x1 = uv[2], y1 = uv[3], x2 = uv[4], y2 = uv[5];
    const double area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
    if (!(std::abs(area) > 0)) continue;
    const int iMin = std::max(chart.x, int(std::floor(std::min({x0, x1, x2})))),
              iMax = std::min(chart.x + width - 1, int(std::floor(std::max({x0, x1, x2})))),
              jMin = std::max(chart.y, int(std::floor(std::min({y0, y1, y2})))),
              jMax = std::min(chart.y + height - 1, int(std::floor(std::max({y0, y1, y2}))));
    const LightmapTriangle &triangle = triangles[t];
    for (int j = jMin; j <= jMax; ++j)
      for (int i = iMin; i <= iMax; ++i)
        for (int sy = 0; sy < samples; ++sy)
          for (int sx = 0; sx < samples; ++sx) {
            const double x = i + (sx + 0.5) / samples, y = j + (sy + 0.5) / samples;
            // Barycentrics in the atlas; a point on a shared edge counts in both triangles (equal weight).
            const double b1 = ((x - x0) * (y2 - y0) - (x2 - x0) * (y - y0)) / area;
            const double b2 = ((x1 - x0) * (y - y0) - (x - x0) * (y1 - y0)) / area;
            const double b0 = 1 - b1 - b2;
            if (b0 < 0 || b1 < 0 || b2 < 0) continue;
            const double b[3] = {b0, b1, b2};
            const Vec3 p = triangle.corners[0] * b0 + triangle.corners[1] * b1 + triangle.corners[2] * b2;
            if (!reader.visible(triangle.face, p)) continue;
            const SurfaceLight light = reader.read(triangle, p, b);
            const size_t local = size_t(j - chart.y) * size_t(width) + size_t(i - chart.x);
            for (int c = 0; c < 3; ++c) {
              sums[6 * local + size_t(c)] += light.irradiance[c];
              sums[6 * local + 3 + size_t(c)] += light.radiance[c];
            }
            ++counts[local];
          }
  }
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const size_t local = size_t(j) * size_t(width) + size_t(i);
      if (!counts[local]) continue;
      const size_t texel = size_t(chart.y + j) * size_t(out.width) + size_t(chart.x + i);
      for (size_t c = 0; c < 3; ++c) {
        out.irradiance[3 * texel + c] = float(sums[6 * local + c] / counts[local]);
        out.radiance[3 * texel + c] = float(sums[6 * local + 3 + c] / counts[local]);
      }
      out.covered[texel] = 1;
    }
}

/// Ring after ring, every empty texel next to a filled one takes its filled eight neighbours' mean.
void dilate(LightmapImages &images, int rings) {
  const int w = images.width, h = images.height;
  std::vector<size_t> ring;
  for (int r = 0; r < rings; ++r) {
    ring.clear();
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        if (images.covered[size_t(y) * size_t(w) + size_t(x)]) continue;
        bool next = false;
        for (int dy = -1; dy <= 1 && !next; ++dy)
          for (int dx = -1; dx <= 1 && !next; ++dx) {
            const int nx = x + dx, ny = y + dy;
            next = nx >= 0 && ny >= 0 && nx < w && ny < h && images.covered[size_t(ny) * size_t(w) + size_t(nx)];
          }
        if (next) ring.push_back(size_t(y) * size_t(w) + size_t(x));
      }
    if (ring.empty()) return;
    for (size_t texel : ring) {
      const int x = int(texel % size_t(w)), y = int(texel / size_t(w));
      double irradiance[3] = {0, 0, 0}, radiance[3] = {0, 0, 0};
      int n = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
          const size_t other = size_t(ny) * size_t(w) + size_t(nx);
          if (!images.covered[other]) continue;
          for (size_t c = 0; c < 3; ++c) irradiance[c] += images.irradiance[3 * other + c];
          for (size_t c = 0; c < 3; ++c) radiance[c] += images.radiance[3 * other + c];
          ++n;
        }
      for (size_t c = 0; c < 3; ++c) {
        images.irradiance[3 * texel + c] = float(irradiance[c] / n);
        images.radiance[3 * texel + c] = float(radiance[c] / n);
      }
    }
    for (size_t texel : ring) images.covered[texel] = 2;  // after the ring: its texels read only the ones before
  }
}

}  // namespace

std::vector<LightmapTriangle> lightmapTriangles(const Scene &scene, const Solution &solution) {
  const RadiosityMesh &mesh = solution.mesh;
  std::vector<std::vector<uint32_t>> trianglesOfFace(scene.faces.size());
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) trianglesOfFace[scene.triangles[t].face].push_back(t);
  std::vector<LightmapTriangle> out;
  for (uint32_t f = 0; f < scene.faces.size(); ++f) {
    if (f >= mesh.patchOfFace.size() || mesh.patchOfFace[f] < 0) continue;
    // A two-sided surface's back (Scene::addBackFaces) is a face with triangles of its own, wound the other way.
    for (uint32_t t : trianglesOfFace[f]) {
      const Triangle &triangle = scene.triangles[t];
      LightmapTriangle lt;
      lt.face = f;
      lt.triangle = t;
      for (int k = 0; k < 3; ++k) lt.corners[k] = scene.positions[triangle.v[k]];
      out.push_back(lt);
    }
  }
  return out;
}

LightmapImages bakeLightmap(const Scene &scene, const Solution &solution, std::span<const LightmapTriangle> triangles,
                            const LightmapAtlas &atlas, const LightmapBakeOptions &options) {
  LightmapImages images;
  images.width = atlas.width;
  images.height = atlas.height;
  const size_t texels = size_t(atlas.width) * size_t(atlas.height);
  images.irradiance.assign(3 * texels, 0.0f);
  images.radiance.assign(3 * texels, 0.0f);
  images.covered.assign(texels, 0);
  const SolutionReader reader(scene, solution);
  const int samples = std::max(options.samples, 1);
  {
    Phase phase("baking the lightmap", atlas.charts.size());
    // Charts own disjoint rectangles: each writes only its own texels.
    tbb::parallel_for(size_t(0), atlas.charts.size(), [&](size_t c) {
      bakeChart(atlas.charts[c], triangles, atlas, reader, samples, images);
      phase.advance();
    });
  }
  for (uint8_t c : images.covered) images.coveredTexels += c == 1;
  dilate(images, options.dilation);
  return images;
}

}  // namespace radiant
