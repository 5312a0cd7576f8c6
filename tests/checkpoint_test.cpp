// Render checkpoints (render/checkpoint.h): a render stopped at any point and
// resumed from its checkpoint ends with the very film of a run that never
// stopped, bit for bit; a checkpoint of another job, or a damaged one, is
// refused with the file named.
#include "render/checkpoint.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "render/driver.h"
#include "render/multipass_checkpoint.h"
#include "util/error.h"
#include "util/interrupt.h"

namespace radiant {
namespace {

/// Noisy radiance with an edge: every sample's value depends on its own
/// random numbers, so a sample taken twice, skipped or taken out of order
/// changes the film's sums.
class NoisyEdge final : public Renderer {
 public:
  explicit NoisyEdge(bool onlyAcrossThePixel) : onlyAcrossThePixel_(onlyAcrossThePixel) {}
  Bands radiance(const Ray &ray, Sampler &rng) const override {
    const double edge = ray.direction.x + 0.3 * ray.direction.y > 0 ? 1.0 : 0.25;
    return onlyAcrossThePixel_ ? Bands(edge) : Bands(edge * (0.5 + rng.next()));
  }
  bool variesOnlyAcrossThePixel() const override { return onlyAcrossThePixel_; }

 private:
  bool onlyAcrossThePixel_;
};

/// Asks for an interrupt (as Ctrl-C or SIGTERM would) at its n-th camera sample.
class StopsAt final : public Renderer {
 public:
  StopsAt(const Renderer &inner, uint64_t n) : inner_(inner), n_(n) {}
  Bands radiance(const Ray &ray, Sampler &rng) const override {
    if (++calls_ == n_) requestInterrupt();
    return inner_.radiance(ray, rng);
  }
  bool variesOnlyAcrossThePixel() const override { return inner_.variesOnlyAcrossThePixel(); }

 private:
  const Renderer &inner_;
  uint64_t n_;
  mutable std::atomic<uint64_t> calls_{0};
};

constexpr int kSize = 64;

struct TempFile {
  std::string path =
      (std::filesystem::temp_directory_path() / ("radiant-checkpoint-test-" + std::to_string(::getpid()) + ".bin"))
          .string();
  ~TempFile() { std::filesystem::remove(path); }
};

DriverOptions options(const std::string &checkpoint) {
  DriverOptions o;
  o.samplesPerPixel = 64;
  o.threads = 2;
  o.tileSize = 8;  // 64 tiles: four waves a round, a checkpoint after each
  o.checkpointPath = checkpoint;
  o.checkpointIntervalSeconds = 0;
  o.resume = true;
  o.checkpointJob = "checkpoint test";
  return o;
}

Film uninterrupted(const Renderer &renderer) {
  Film film(kSize, kSize);
  DriverOptions o = options("");
  renderImage(PinholeCamera(CameraSettings{}, kSize, kSize), renderer, o, film);
  return film;
}

void expectSameFilm(const Film &a, const Film &b) {
  ASSERT_EQ(a.pixelCount(), b.pixelCount());
  size_t differing = 0;
  for (size_t p = 0; p < a.pixelCount(); ++p)
    for (int band = 0; band < kBandCount; ++band)
      differing += a.sum[p][band] != b.sum[p][band] || a.sumSquares[p][band] != b.sumSquares[p][band] ||
                   a.samples[p] != b.samples[p];
  EXPECT_EQ(differing, 0u) << "pixel values differing between the resumed and the uninterrupted film";
}

/// Stops the render at camera sample `stopAt`, then resumes it from its checkpoint.
Film stoppedAndResumed(const Renderer &renderer, uint64_t stopAt, const std::string &checkpoint, int *resumedFrom) {
  const PinholeCamera camera(CameraSettings{}, kSize, kSize);
  clearInterrupt();
  {
    Film film(kSize, kSize);
    const StopsAt stopping(renderer, stopAt);
    const RenderStats stats = renderImage(camera, stopping, options(checkpoint), film);
    EXPECT_TRUE(stats.interrupted);
    EXPECT_GE(stats.checkpointsWritten, 1);
  }
  clearInterrupt();
  Film film(kSize, kSize);
  const RenderStats stats = renderImage(camera, renderer, options(checkpoint), film);
  EXPECT_FALSE(stats.interrupted);
  *resumedFrom = stats.resumedFromSamples;
  return film;
}

TEST(RenderCheckpoint, AResumedRenderEqualsTheUninterruptedOneWhereverItStopped) {
  const NoisyEdge renderer(false);
  const Film reference = uninterrupted(renderer);
  // Samples: 64² pixels × 64 spp in rounds of 1, 1, 2, 4, … Stops in the
  // first round, in the middle of later ones and near the end.
  for (uint64_t stopAt : {1000ull, 20000ull, 70000ull, 200000ull, 260000ull}) {
    SCOPED_TRACE(stopAt);
    TempFile checkpoint;
    int resumedFrom = -1;
    expectSameFilm(stoppedAndResumed(renderer, stopAt, checkpoint.path, &resumedFrom), reference);
    EXPECT_GE(resumedFrom, 0) << "the second run carried on from the checkpoint";
  }
}

TEST(RenderCheckpoint, ConvergedPixelsStayStoppedAcrossAResume) {
  // The radiosity displays' converged pixels (render/driver.h) are part of the state.
  const NoisyEdge renderer(true);
  const Film reference = uninterrupted(renderer);
  TempFile checkpoint;
  int resumedFrom = -1;
  // 64² pixels × 8 samples before any pixel may stop (32 768 samples), then only the ~200 the edge crosses.
  const Film resumed = stoppedAndResumed(renderer, 36000, checkpoint.path, &resumedFrom);
  expectSameFilm(resumed, reference);
  EXPECT_GE(resumedFrom, kMinimumSamples);
}

/// The message of the InputError that reading `path` raises (which must name
/// the file), or "" when it reads.
template <typename Read>
std::string refusalOf(const std::string &path, const Read &read) {
  try {
    read();
  } catch (const InputError &e) {
    EXPECT_EQ(e.location().file, path);
    return std::string(e.message());
  }
  return std::string();
}

TEST(RenderCheckpoint, ACheckpointOfAnotherJobOrADamagedOneIsRefused) {
  TempFile checkpoint;
  RenderCheckpoint state;
  state.job = "another job";
  state.tileSize = 8;
  state.tileDone.assign(64, 0);
  state.active.assign(size_t(kSize) * kSize, 1);
  Film film(kSize, kSize);
  writeRenderCheckpoint(checkpoint.path, state, film);
  auto refusal = [&](const std::string &job, int width) {
    return refusalOf(checkpoint.path, [&] {
      Film target(width, kSize);
      RenderCheckpoint read;
      readRenderCheckpoint(checkpoint.path, job, read, target);
    });
  };
  EXPECT_EQ(refusal("another job", kSize), "");
  EXPECT_NE(refusal("checkpoint test", kSize).find("another job"), std::string::npos);
  EXPECT_NE(refusal("another job", kSize / 2).find("32x64"), std::string::npos);
  // Truncated: the film cut short.
  std::filesystem::resize_file(checkpoint.path, std::filesystem::file_size(checkpoint.path) - 100);
  EXPECT_NE(refusal("another job", kSize).find("truncated"), std::string::npos);
  // Not a checkpoint at all.
  std::ofstream(checkpoint.path) << "{\"version\": 1, \"camera\": {\"eye\": [0, 1, 3]}, \"image\": {\"width\": 64}}";
  EXPECT_NE(refusal("another job", kSize).find("RADIANT-CHECKPOINT"), std::string::npos);
}

// multipass's checkpoint (render/multipass_checkpoint.h): read back as
// written; another job's, another size's, a file cut anywhere, one with
// impossible counts, or not one at all is refused naming the file.
TEST(MultipassCheckpoint, ReadsBackAndRefusesAnotherJobsOrADamagedOne) {
  TempFile checkpoint;
  constexpr int kWidth = 8, kHeight = 4;
  ControlVariateImage combined(kWidth, kHeight);
  Film pairs(kWidth, kHeight, {"control"});
  pairs.add(5, Bands(2.0), std::vector<Bands>{Bands(1.5)}.data());
  combined.addPairs(pairs);
  MultipassCheckpoint state;
  state.job = "job A";
  state.pass = 7, state.paired = false, state.samplesPerPixel = 24;
  state.elapsedSeconds = 1.5, state.unitsSpent = 12, state.pairedCost = 0.25;
  writeMultipassCheckpoint(checkpoint.path, state, combined);
  const MultipassCheckpoint read = readMultipassCheckpoint(checkpoint.path, "job A", kWidth, kHeight);
  EXPECT_EQ(read.pass, 7);
  EXPECT_FALSE(read.paired);
  EXPECT_EQ(read.samplesPerPixel, 24);
  EXPECT_EQ(read.elapsedSeconds, 1.5);
  EXPECT_EQ(read.unitsSpent, 12);
  EXPECT_EQ(read.pairedCost, 0.25);
  EXPECT_EQ(read.sums.pairedSpp, combined.pairedSamples());
  EXPECT_EQ(read.sums.pairs.sumDifference[5][0], 0.5);
  EXPECT_EQ(read.sums.controls.sum[5][0], 1.5);
  auto refusal = [&](const std::string &job, int width) {
    return refusalOf(checkpoint.path, [&] { readMultipassCheckpoint(checkpoint.path, job, width, kHeight); });
  };
  EXPECT_NE(refusal("job B", kWidth).find("another job"), std::string::npos);
  EXPECT_NE(refusal("job A", 2 * kWidth).find("8x4"), std::string::npos);
  // Cut anywhere: a clear refusal, never a crash.
  const std::string whole = [&] {
    std::ifstream in(checkpoint.path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  for (size_t size = 0; size < whole.size(); size += 1 + size / 8) {
    std::ofstream(checkpoint.path, std::ios::binary) << whole.substr(0, size);
    EXPECT_NE(refusal("job A", kWidth), "") << "cut at " << size;
  }
  // Impossible counts: a pass before 3.
  std::string bad = whole;
  const size_t passOffset = std::string("RADIANT-MULTIPASS").size() + 4 + 4 + 5 + 3 * 4;
  bad[passOffset] = 1;
  std::ofstream(checkpoint.path, std::ios::binary) << bad;
  EXPECT_NE(refusal("job A", kWidth).find("impossible"), std::string::npos);
  std::ofstream(checkpoint.path, std::ios::binary) << "RADIANT-CHECKPOINT and more";
  EXPECT_NE(refusal("job A", kWidth).find("RADIANT-MULTIPASS"), std::string::npos);
}

}  // namespace
}  // namespace radiant
