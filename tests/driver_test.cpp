// The render driver (render/driver.h): converged pixels stop, for the
// renderers whose estimate varies only across the pixel, and the image still
// depends on nothing but the seed and the sample count; an interrupt is heard
// within a second or so however slow the method.
#include "render/driver.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "util/interrupt.h"

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
  constexpr int kSize = 24;
  auto crossed = [&](int x, int y) {
    const double mean = r.film.mean(size_t(y) * kSize + size_t(x))[0];
    return mean != 1.0 && mean != 0.25;
  };
  int stopped = 0, full = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const uint32_t n = r.film.samples[size_t(y) * kSize + size_t(x)];
      if (crossed(x, y)) {
        ++full;
        EXPECT_GT(n, uint32_t(kMinimumSamples)) << "a pixel the line crosses keeps sampling";
        continue;
      }
      // The line misses it: every sample agreed from the start. It stops,
      // unless a neighbour the line crosses is an edge beside it.
      bool besideTheLine = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          besideTheLine = besideTheLine || (nx >= 0 && ny >= 0 && nx < kSize && ny < kSize && crossed(nx, ny));
        }
      if (!besideTheLine) {
        EXPECT_EQ(n, uint32_t(kMinimumSamples));
        ++stopped;
      }
    }
  EXPECT_GT(stopped, 350);
  EXPECT_GT(full, 10);
  EXPECT_EQ(r.stats.samplesPerPixel, 256);
  EXPECT_LT(r.stats.cameraSamples, uint64_t(256) * r.film.pixelCount() / 4);
}

/// Radiance 100 to the right of a vertical line through the image at
/// x = column + 0.97 pixels, 0.25 to its left: the line barely crosses the
/// pixels of `column` (3 % of each), beside a bright uniform column.
class BarelyCrossedColumn final : public Renderer {
 public:
  BarelyCrossedColumn(const PinholeCamera &camera, int column, int height) {
    const double x = column + 0.97;
    normal_ = cross(camera.generateRay(x, 0).direction, camera.generateRay(x, height).direction);
    if (dot(normal_, camera.generateRay(column + 2, height / 2.0).direction) < 0) normal_ = -normal_;
  }
  Bands radiance(const Ray &ray, Sampler &) const override {
    return Bands(dot(normal_, ray.direction) > 0 ? 100.0 : 0.25);
  }
  bool variesOnlyAcrossThePixel() const override { return true; }

 private:
  Vec3 normal_;
};

TEST(Driver, APixelAnEdgeBarelyCrossesDoesNotStopOnItsFirstSamples) {
  // Each pixel of column 10 has its first 8 samples all on the dim side
  // with probability 0.97⁸ = 78 %: a zero variance that says nothing about
  // the light beside it. Its bright neighbour marks it as an edge, so it
  // takes every sample, and the column's mean comes out at the coverage's
  // 0.25 + 0.03 · 99.75 = 3.24 (σ of one pixel's mean ≤ 99.75·√(0.03·0.97/256)
  // = 1.06, of the column's 24 ≤ 0.22: 4σ is 0.9).
  constexpr int kSize = 24, kColumn = 10, kSpp = 256;
  const PinholeCamera camera(CameraSettings{}, kSize, kSize);
  const BarelyCrossedColumn renderer(camera, kColumn, kSize);
  Film film(kSize, kSize);
  DriverOptions options;
  options.samplesPerPixel = kSpp;
  renderImage(camera, renderer, options, film);
  double mean = 0;
  for (int y = 0; y < kSize; ++y) {
    const size_t p = size_t(y) * kSize + kColumn;
    EXPECT_EQ(film.samples[p], uint32_t(kSpp)) << "row " << y;
    mean += film.mean(p)[0] / kSize;
  }
  EXPECT_NEAR(mean, 0.25 + 0.03 * 99.75, 0.9);
  // Its neighbours on the dim side are uniform and stop: only the edge goes on.
  for (int y = 0; y < kSize; ++y) EXPECT_EQ(film.samples[size_t(y) * kSize + kColumn - 2], uint32_t(kMinimumSamples));
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

/// A slow method: half a millisecond a sample (reichert's order), its value the sample's index.
class Slow final : public Renderer {
 public:
  Bands radiance(const Ray &, Sampler &rng) const override {
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    return Bands(rng.next());
  }
};

TEST(Driver, ASlowMethodHearsAnInterruptWithinASecondOrSo) {
  // One 16 × 16 tile on one thread: a sample per pixel takes 0.13 s or more.
  // The interrupt comes 0.1 s into the round that starts at 8 spp. Doubling,
  // that round would be 8 spp, over a second, the interrupt heard only at its
  // end; cut to about a second a tile, it ends within one.
  const Slow slow;
  const PinholeCamera camera(CameraSettings{}, 16, 16);
  Film film(16, 16);
  DriverOptions options;
  options.samplesPerPixel = 1 << 20;
  options.threads = 1;
  clearInterrupt();
  std::atomic<bool> roundStarted{false};
  std::thread interrupter([&] {
    while (!roundStarted) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    requestInterrupt();
  });
  std::chrono::steady_clock::time_point roundStart;
  const RenderStats stats = renderImage(camera, slow, options, film, [&](const Progress &p) {
    if (p.samplesDone >= 8 && !roundStarted) roundStart = std::chrono::steady_clock::now(), roundStarted = true;
  });
  interrupter.join();
  clearInterrupt();
  ASSERT_TRUE(roundStarted);
  const double heard = std::chrono::duration<double>(std::chrono::steady_clock::now() - roundStart).count() - 0.1;
  EXPECT_TRUE(stats.interrupted);
  EXPECT_LT(heard, 1.4) << "stopped " << heard << " s after the interrupt, at " << stats.samplesPerPixel << " spp";
}

}  // namespace
}  // namespace radiant
