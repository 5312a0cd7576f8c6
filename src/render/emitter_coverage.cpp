#include "render/emitter_coverage.h"

#include <tbb/parallel_for.h>

namespace radiant {

std::vector<float> emitterCoverage(const RayTracer &tracer, const PinholeCamera &camera, int width, int height) {
  constexpr int n = kEmitterCoverageGrid;
  const Scene &scene = tracer.scene();
  std::vector<float> coverage(size_t(width) * height, 0.0f);
  tbb::parallel_for(0, height, [&](int y) {
    std::vector<Ray> rays(size_t(width) * n * n);
    std::vector<HitRecord> hits(rays.size());
    for (int x = 0; x < width; ++x)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          rays[(size_t(x) * n + j) * n + i] = camera.generateRay(x + (i + 0.5) / n, y + (j + 0.5) / n);
    tracer.intersectMany(rays, hits);
    for (int x = 0; x < width; ++x) {
      int hitEmitter = 0;
      for (int k = 0; k < n * n; ++k) {
        const size_t r = size_t(x) * n * n + k;
        if (!hits[r].found()) continue;
        const Triangle &triangle = scene.triangles[hits[r].triangle];
        if (scene.materials[triangle.material].isEmitter() &&
            dot(rays[r].direction, scene.triangleNormal(triangle)) < 0)
          ++hitEmitter;
      }
      coverage[size_t(y) * width + x] = float(hitEmitter) / float(n * n);
    }
  });
  return coverage;
}

}  // namespace radiant
