// The render driver (render/driver.h): converged pixels stop, for the
// renderers whose estimate varies only across the pixel, and the image still
// depends on nothing but the seed and the sample count.
#include "render/driver.h"

#include <gtest/gtest.h>

namespace radiant {
namespace {

/// Radiance 1 on one side of a tilted line through the image, 0.25 on the
/// other: a pixel the line misses is uniform, one it crosses is not.
class TiltedEdge final : public Renderer {
 public:
  explicit TiltedEdge(bool onlyAcrossThePixel) : onlyAcrossThePixel_(onlyAcrossThePixel) {}
  Bands radiance(const Ray &ray, Sampler &) const override {
    return Bands(ray.direction.x + 0.3 * ray.direction.y > 0 ? 1.0 : 0.25);
  }
  bool variesOnlyAcrossThePixel() const override { return onlyAcrossThePixel_; }

 private:
  bool onlyAcrossThePixel_;
};

struct Rendered {
  Film film;
  RenderStats stats;
};

Rendered render(const Renderer &renderer, int threads, int spp = 256) {
  constexpr int kSize = 24;
  const PinholeCamera camera(CameraSettings{}, kSize, kSize);
  Rendered r{Film(kSize, kSize), {}};
  DriverOptions options;
  options.samplesPerPixel = spp;
  options.threads = threads;
  r.stats = renderImage(camera, renderer, options, r.film);
  return r;
}

TEST(Driver, UniformPixelsStopAfterTheMinimumAndEdgePixelsGoOn) {
  const TiltedEdge edge(true);
  const Rendered r = render(edge, 2);
  int stopped = 0, full = 0;
  for (size_t p = 0; p < r.film.pixelCount(); ++p) {
    const uint32_t n = r.film.samples[p];
    const double mean = r.film.mean(p)[0];
    if (mean == 1.0 || mean == 0.25) {
      // The line misses it: every sample agreed from the start.
      EXPECT_EQ(n, uint32_t(kMinimumSamples));
      ++stopped;
    } else {
      ++full;
      EXPECT_GT(n, uint32_t(kMinimumSamples)) << "a pixel the line crosses keeps sampling";
    }
  }
  EXPECT_GT(stopped, 400);
  EXPECT_GT(full, 10);
  EXPECT_EQ(r.stats.samplesPerPixel, 256);
  EXPECT_LT(r.stats.cameraSamples, uint64_t(256) * r.film.pixelCount() / 4);
}

TEST(Driver, ARendererThatIsNotJustAntialiasingTakesEverySample) {
  const TiltedEdge edge(false);
  const Rendered r = render(edge, 2, 64);
  for (size_t p = 0; p < r.film.pixelCount(); ++p) EXPECT_EQ(r.film.samples[p], 64u);
}

TEST(Driver, StoppingPixelsDoesNotDependOnTheThreadCount) {
  const TiltedEdge edge(true);
  const Rendered one = render(edge, 1), two = render(edge, 2);
  for (size_t p = 0; p < one.film.pixelCount(); ++p) {
    ASSERT_EQ(one.film.samples[p], two.film.samples[p]);
    ASSERT_EQ(one.film.sum[p][0], two.film.sum[p][0]);
  }
}

}  // namespace
}  // namespace radiant
