// Two path-traced images of scenes that should be the same (a file read back,
// a format converted), compared by sums over regions with their variances:
// what the round-trip tests share.
#pragma once

#include "raytrace/ray_tracer.h"
#include "render/driver.h"
#include "render/registry.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace radiant::test {

/// `scene` path-traced through `camera` at size × size, spp samples per pixel, every pixel to the end.
inline Film pathTraced(const Scene &scene, const CameraSettings &camera, int size, int spp, uint64_t seed) {
  RayTracer tracer(scene);
  Film film(size, size);
  DriverOptions driver;
  driver.samplesPerPixel = spp;
  driver.seed = seed;
  driver.stopConvergedPixels = false;
  renderImage(PinholeCamera(camera, size, size), *createRenderer("path", tracer, RenderContext{}), driver, film);
  return film;
}

/// The band-average sums of two films over a rectangle of pixels, and the variance of their difference.
struct RegionSums {
  double a = 0, b = 0, variance = 0;
};
inline RegionSums regionSums(const Film &a, const Film &b, int x0, int y0, int width, int height) {
  RegionSums s;
  for (int y = y0; y < y0 + height; ++y)
    for (int x = x0; x < x0 + width; ++x) {
      const size_t p = size_t(y) * size_t(a.width) + size_t(x);
      s.a += a.mean(p).average();
      s.b += b.mean(p).average();
      s.variance += a.varianceOfMean(p).average() + b.varianceOfMean(p).average();
    }
  return s;
}

}  // namespace radiant::test
