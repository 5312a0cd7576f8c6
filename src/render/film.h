// The film: linear radiance per band per pixel, with the running statistics a
// variance image needs. Box filter: each camera sample counts fully for the
// pixel it falls in.
#pragma once

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "util/spectrum.h"

namespace radiant {

/// A named extra output of every sample beside its radiance (Mitsuba 3's
/// AOVs): the work selective re-evaluation did, the control of multipass's
/// control variate, … (Renderer::channels). Besides the channel's own sums
/// the film keeps those of the radiance's difference from it — what using
/// the channel as a control variate C needs (render/control_variate.h): Σ(L − C),
/// Σ(L − C)² and ΣC·(L − C), each added per sample.
struct FilmChannel {
  std::string name;
  std::vector<Bands> sum, sumSquares, sumDifference, sumDifferenceSquares, sumProducts;

  FilmChannel() = default;
  FilmChannel(std::string channelName, size_t pixels)
      : name(std::move(channelName)),
        sum(pixels),
        sumSquares(pixels),
        sumDifference(pixels),
        sumDifferenceSquares(pixels),
        sumProducts(pixels) {}
  void add(size_t pixel, const Bands &radiance, const Bands &value) {
    const Bands difference = radiance - value;
    sum[pixel] += value;
    sumSquares[pixel] += value * value;
    sumDifference[pixel] += difference;
    sumDifferenceSquares[pixel] += difference * difference;
    sumProducts[pixel] += value * difference;
  }
};

struct Film {
  int width = 0, height = 0;
  std::vector<Bands> sum;             ///< Σ radiance, W·sr⁻¹·m⁻²
  std::vector<Bands> sumSquares;      ///< Σ radiance², for the variance estimate
  std::vector<uint32_t> samples;      ///< sample count per pixel
  std::vector<FilmChannel> channels;  ///< the extra outputs asked for, filled by the driver

  Film() = default;
  Film(int w, int h, const std::vector<std::string> &channelNames = {})
      : width(w), height(h), sum(size_t(w) * h), sumSquares(size_t(w) * h), samples(size_t(w) * h) {
    for (const std::string &name : channelNames) channels.emplace_back(name, pixelCount());
  }

  size_t pixelCount() const { return size_t(width) * height; }
  /// The bytes a pixel takes: the sums, the sample count and each channel's five sums.
  static constexpr size_t bytesPerPixel(size_t channelCount) {
    return 2 * sizeof(Bands) + sizeof(uint32_t) + channelCount * 5 * sizeof(Bands);
  }
  /// No samples again, keeping the memory: a film reused pass after pass
  /// (multipass) is not allocated, zeroed by the kernel page by page and
  /// freed every pass (35–50 ms a pass at 256²).
  void clear() {
    std::fill(sum.begin(), sum.end(), Bands(0.0));
    std::fill(sumSquares.begin(), sumSquares.end(), Bands(0.0));
    std::fill(samples.begin(), samples.end(), 0u);
    for (FilmChannel &c : channels)
      for (std::vector<Bands> *v : {&c.sum, &c.sumSquares, &c.sumDifference, &c.sumDifferenceSquares, &c.sumProducts})
        std::fill(v->begin(), v->end(), Bands(0.0));
  }
  /// One sample: its radiance and, when the film has channels, their values in the film's order.
  void add(size_t pixel, const Bands &radiance, const Bands *channelValues = nullptr) {
    sum[pixel] += radiance;
    sumSquares[pixel] += radiance * radiance;
    ++samples[pixel];
    if (channelValues)
      for (size_t c = 0; c < channels.size(); ++c) channels[c].add(pixel, radiance, channelValues[c]);
  }
  /// The channel of that name, or nullptr.
  const FilmChannel *channel(const std::string &name) const {
    for (const FilmChannel &c : channels)
      if (c.name == name) return &c;
    return nullptr;
  }
  /// The pixel's estimate: mean radiance.
  Bands mean(size_t pixel) const { return samples[pixel] ? sum[pixel] / samples[pixel] : Bands(0.0); }
  /// Adds another film's samples (same size): the mean of all samples of both.
  void accumulate(const Film &other) {
    for (size_t p = 0; p < pixelCount(); ++p)
      sum[p] += other.sum[p], sumSquares[p] += other.sumSquares[p], samples[p] += other.samples[p];
    for (FilmChannel &c : channels)
      if (const FilmChannel *o = other.channel(c.name))
        for (size_t p = 0; p < pixelCount(); ++p) {
          c.sum[p] += o->sum[p], c.sumSquares[p] += o->sumSquares[p], c.sumDifference[p] += o->sumDifference[p];
          c.sumDifferenceSquares[p] += o->sumDifferenceSquares[p], c.sumProducts[p] += o->sumProducts[p];
        }
  }
  /// Variance of the pixel's mean (sample variance / n), per band.
  Bands varianceOfMean(size_t pixel) const {
    uint32_t n = samples[pixel];
    if (n < 2) return Bands(0.0);
    Bands m = sum[pixel] / n;
    Bands v = (sumSquares[pixel] / n - m * m) * (1.0 / (n - 1));
    for (int b = 0; b < kBandCount; ++b) v[b] = std::max(0.0, v[b]);
    return v;
  }
};

/// Every per-pixel array of a film (Film or const Film), in one fixed order:
/// `bands(vector<Bands>&)` for the sums, `counts(vector<uint32_t>&)` for the
/// sample counts. What a checkpoint writes and the ranks of a job sum.
template <typename AnyFilm, typename BandsArray, typename CountArray>
void forEachFilmArray(AnyFilm &film, const BandsArray &bands, const CountArray &counts) {
  bands(film.sum);
  bands(film.sumSquares);
  counts(film.samples);
  for (auto &c : film.channels)
    for (auto *v : {&c.sum, &c.sumSquares, &c.sumDifference, &c.sumDifferenceSquares, &c.sumProducts}) bands(*v);
}

/// Paired samples: per pixel the sums a control variate needs — of the
/// control R, of the difference D = radiance − R, of their squares and of
/// their product (render/control_variate.h); a film's channel holds them
/// (FilmChannel), and PairedFilm(film, name) takes them from it.
struct PairedFilm {
  int width = 0, height = 0;
  std::vector<Bands> sumControl, sumControlSquares, sumDifference, sumDifferenceSquares, sumProducts;
  std::vector<uint32_t> samples;

  PairedFilm() = default;
  PairedFilm(int w, int h)
      : width(w),
        height(h),
        sumControl(size_t(w) * h),
        sumControlSquares(size_t(w) * h),
        sumDifference(size_t(w) * h),
        sumDifferenceSquares(size_t(w) * h),
        sumProducts(size_t(w) * h),
        samples(size_t(w) * h) {}

  /// The sums of `film`'s channel `channel` as control (it must have it).
  PairedFilm(const Film &film, const std::string &channel) : width(film.width), height(film.height) {
    const FilmChannel *c = film.channel(channel);
    if (!c) throw std::logic_error("the film has no channel '" + channel + "'");
    sumControl = c->sum, sumControlSquares = c->sumSquares, sumDifference = c->sumDifference;
    sumDifferenceSquares = c->sumDifferenceSquares, sumProducts = c->sumProducts, samples = film.samples;
  }

  size_t pixelCount() const { return size_t(width) * height; }
  /// The bytes a pixel takes: the sums, the sample count and each channel's five sums.
  static constexpr size_t bytesPerPixel(size_t channelCount) {
    return 2 * sizeof(Bands) + sizeof(uint32_t) + channelCount * 5 * sizeof(Bands);
  }
  /// Adds another paired film's samples (same size).
  void accumulate(const PairedFilm &other) {
    for (size_t p = 0; p < pixelCount(); ++p) {
      sumControl[p] += other.sumControl[p], sumControlSquares[p] += other.sumControlSquares[p];
      sumDifference[p] += other.sumDifference[p], sumDifferenceSquares[p] += other.sumDifferenceSquares[p];
      sumProducts[p] += other.sumProducts[p], samples[p] += other.samples[p];
    }
  }
};

}  // namespace radiant
