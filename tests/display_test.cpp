// The display mapping (src/display/, docs/tone-mapping.md): that document's
// test vectors for gamma, sRGB, Tumblin–Rushmeier and Ward, the firefly and
// the searchlight, and the files the mapping reads and writes.
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numeric>

#include "display/display_mapping.h"
#include "display/emitter_mask.h"
#include "display/false_colour.h"
#include "display/luminance.h"
#include "display/tone_operator.h"
#include "io/image.h"
#include "raytrace/ray_tracer.h"
#include "render/emitter_coverage.h"
#include "scene/load_scene.h"
#include "temp_dir.h"
#include "util/error.h"

namespace radiant {
namespace {

/// A one-pixel grey image of the given luminance in cd/m².
Image greyPixel(double luminanceCdM2) {
  Image image(1, 1);
  for (int c = 0; c < 3; ++c) image.rgb[c] = float(luminanceCdM2 / kLuminousEfficacy);
  return image;
}

/// The encoded value V of a one-pixel grey image under `settings`.
double encodeGrey(double luminanceCdM2, const DisplaySettings &settings) {
  Image image = greyPixel(luminanceCdM2);
  DisplayMapping mapping(image, settings);
  double v[3];
  mapping.encode(image.pixel(0, 0), v);
  EXPECT_NEAR(v[0], v[1], 1e-6);
  EXPECT_NEAR(v[0], v[2], 1e-6);
  return v[1];
}

double mean8Bit(const std::vector<uint16_t> &values) {
  return std::accumulate(values.begin(), values.end(), 0.0) / double(values.size());
}

// ---- Gamma, sRGB (IEC 61966-2-1), quantisation, gamut ----

TEST(Gamma, ReferenceVectors) {
  // I = k·V^γ (Tumblin & Rushmeier 1993, eq. 5): γ = 2.2, I/k = 0.18 → 117,
  // 0.5 → 186, 1 → 255.
  EXPECT_EQ(quantise(gammaEncode(0.18, 2.2), 8), 117);
  EXPECT_EQ(quantise(gammaEncode(0.5, 2.2), 8), 186);
  EXPECT_EQ(quantise(gammaEncode(1.0, 2.2), 8), 255);
  EXPECT_EQ(quantise(gammaEncode(4.0, 2.2), 8), 255);
  EXPECT_EQ(quantise(gammaEncode(0.0, 2.2), 8), 0);
}

TEST(Gamma, KnownRadianceGivesKnown8BitValueThroughTheWholeMapping) {
  // linear, exposure 0: radiance 0.18 W·sr⁻¹·m⁻² is I/k = 0.18.
  DisplaySettings settings;
  settings.transfer = TransferCurve::Gamma;
  settings.gamma = 2.2;
  for (auto [relative, expected] : {std::pair{0.18, 117}, {0.5, 186}, {1.0, 255}}) {
    Image image(1, 1);
    image.rgb = {float(relative), float(relative), float(relative)};
    EXPECT_EQ(DisplayMapping(image, settings).quantiseImage(image)[0], expected) << relative;
  }
  // Ward with L_wa = L_dmax/2 has m = 1, so L_d = L_w and I/k = L_w / L_dmax (display max = k).
  settings.toneOperator = "ward";
  settings.parameters.adaptationCdM2 = 50;
  EXPECT_NEAR(encodeGrey(50, settings), std::pow(0.5, 1 / 2.2), 1e-7);  // float pixel
}

TEST(Srgb, ReferenceVectors) {
  EXPECT_NEAR(srgbEncode(0.18), 0.461356, 1e-6);
  EXPECT_NEAR(srgbEncode(0.5), 0.735357, 1e-6);
  EXPECT_EQ(quantise(srgbEncode(0.18), 8), 118);
  // The two pieces meet at C = 0.0031308 (both 0.0404499).
  EXPECT_NEAR(12.92 * 0.0031308, 0.0404499, 1e-7);
  EXPECT_NEAR(srgbEncode(0.0031308), 0.0404499, 1e-7);
  EXPECT_NEAR(srgbEncode(0.0031308 + 1e-12), 0.0404499, 1e-7);
  for (double c : {0.0, 0.001, 0.0031308, 0.01, 0.18, 0.5, 0.9, 1.0}) EXPECT_NEAR(srgbDecode(srgbEncode(c)), c, 1e-12);
  EXPECT_EQ(quantise(1.0, 16), 65535);
  EXPECT_EQ(quantise(0.5, 16), 32768);
}

TEST(Gamut, ClipAndHue) {
  double clip[3] = {2.0, 1.0, 0.5}, hue[3] = {2.0, 1.0, 0.5};
  applyGamutRule(GamutRule::Clip, clip);
  applyGamutRule(GamutRule::Hue, hue);
  EXPECT_DOUBLE_EQ(clip[0], 1);
  EXPECT_DOUBLE_EQ(clip[1], 1);
  EXPECT_DOUBLE_EQ(clip[2], 0.5);
  EXPECT_DOUBLE_EQ(hue[0], 1);
  EXPECT_DOUBLE_EQ(hue[1], 0.5);
  EXPECT_DOUBLE_EQ(hue[2], 0.25);
  double odd[3] = {NAN, -1.0, 0.25};
  applyGamutRule(GamutRule::Hue, odd);
  EXPECT_EQ(odd[0], 0);
  EXPECT_EQ(odd[1], 0);
  EXPECT_EQ(odd[2], 0.25);
}

TEST(Luminance, WhiteRadianceIs683CdPerM2) {
  const float white[3] = {1, 1, 1};
  EXPECT_NEAR(luminanceCdPerM2(white), 683.0, 1e-4);
  EXPECT_NEAR(cdPerM2FromLamberts(1.0), 3183.1, 0.05);  // 1 lambert = 10⁴/π cd/m²
  Image image(2, 1);
  image.rgb = {1, 1, 1, 0.01f, 0.01f, 0.01f};  // 683 and 6.83 cd/m²
  LuminanceStatistics s = luminanceStatistics(image);
  EXPECT_NEAR(s.logAverage, 68.3, 1e-3);
  EXPECT_NEAR(s.maximum, 683, 1e-3);
}

TEST(Linear, ByteIdenticalToTheOldPngExposurePath) {
  Image image(4, 1);
  image.rgb = {0.0f, 0.001f, 0.01f, 0.1f, 0.2f, 0.3f, 0.45f, 0.5f, 0.6f, 2.0f, NAN, INFINITY};
  DisplaySettings settings;
  settings.parameters.exposureStops = 1.5;
  std::vector<uint16_t> mapped = DisplayMapping(image, settings).quantiseImage(image);
  for (size_t i = 0; i < image.rgb.size(); ++i)
    EXPECT_EQ(mapped[i], std::lround(255.0 * srgbEncode(image.rgb[i] * std::exp2(1.5)))) << i;
}

// ---- Tumblin & Rushmeier 1993 ----

TEST(TumblinRushmeier, IdentityWhenTheWorldIsAdaptedLikeTheDisplay) {
  const double displayAdaptation = 86 / std::sqrt(35.0);  // eq. 14
  EXPECT_NEAR(displayAdaptation, 14.5367, 1e-4);
  for (double world : {1.0, 10.0, 0.01, 1000.0})
    EXPECT_NEAR(tumblinRushmeierDisplayLuminance(world, displayAdaptation, 86, 35), world, 1e-9 * world);
}

TEST(TumblinRushmeier, ReferenceTable) {
  // The table of docs/tone-mapping.md (eq. 13–15): L_dmax 86, C_max 35, γd 2.2;
  // L_d and the frame-buffer value n.
  struct Row {
    double adaptation, displayLuminance, nAtAdaptation, nAtTenTimes;
  };
  const Row rows[] = {
      {0.001, 2.867, 0.0881, 0.1678}, {1, 9.238, 0.3152, 0.7914}, {100, 20.15, 0.4874, 1}, {1e5, 64.93, 0.8648, 1}};
  DisplaySettings settings;
  settings.toneOperator = "tumblin-rushmeier";
  settings.transfer = TransferCurve::Gamma;
  settings.gamma = 2.2;
  for (const Row &row : rows) {
    SCOPED_TRACE(row.adaptation);
    EXPECT_NEAR(tumblinRushmeierDisplayLuminance(row.adaptation, row.adaptation, 86, 35), row.displayLuminance,
                1e-3 * row.displayLuminance);
    settings.parameters.adaptationCdM2 = row.adaptation;
    EXPECT_EQ(encodeGrey(0.1 * row.adaptation, settings), 0.0);  // below the display's black level
    EXPECT_NEAR(encodeGrey(row.adaptation, settings), row.nAtAdaptation, 1e-3);
    EXPECT_NEAR(encodeGrey(10 * row.adaptation, settings), row.nAtTenTimes, 1e-3);
  }
}

TEST(TumblinRushmeier, AdaptationFromTheImageIsEquation11) {
  // A uniform image: E{log10 L} = log10 L, so L_wa = L · 10^0.84.
  EXPECT_NEAR(tumblinRushmeierAdaptation(10), 10 * std::pow(10, 0.84), 1e-9);
  DisplaySettings fromImage, given;
  fromImage.toneOperator = given.toneOperator = "tumblin-rushmeier";
  given.parameters.adaptationCdM2 = 3 * std::pow(10, 0.84);
  EXPECT_NEAR(encodeGrey(3, fromImage), encodeGrey(3, given), 1e-12);
}

// ---- Ward 1994 ----

TEST(Ward, ReferenceVectors) {
  EXPECT_NEAR(wardScaleFactor(0.001, 100), 47.393, 1e-3);
  EXPECT_NEAR(wardScaleFactor(1, 100), 12.026, 1e-3);
  EXPECT_NEAR(wardScaleFactor(10, 100), 3.2809, 1e-4);
  EXPECT_NEAR(wardScaleFactor(50, 100), 1.0, 1e-12);
  EXPECT_NEAR(wardScaleFactor(100, 100), 0.56720, 1e-5);
  EXPECT_NEAR(wardScaleFactor(1000, 100), 0.073293, 1e-6);
}

TEST(Ward, DefaultAdaptationIsTheLogAverage) {
  Image image(2, 1);
  image.rgb = {1, 1, 1, 0.01f, 0.01f, 0.01f};  // log-average 68.3 cd/m²
  DisplaySettings settings;
  settings.toneOperator = "ward";
  settings.gamut = GamutRule::Hue;
  double v[3];
  DisplayMapping(image, settings).encode(image.pixel(1, 0), v);
  const double expected = srgbEncode(wardScaleFactor(68.3, 100) * 6.83 / 100);
  EXPECT_NEAR(v[0], expected, 1e-5);
}

// ---- Reinhard, ACES ----

TEST(Reinhard, GlobalOperator) {
  EXPECT_DOUBLE_EQ(reinhardCurve(1, std::nullopt), 0.5);
  EXPECT_DOUBLE_EQ(reinhardCurve(3, 3.0), 1.0);  // L = L_white maps to white
  EXPECT_EQ(reinhardCurve(0, std::nullopt), 0);
  // A uniform image shows its log-average: 0.18 scaled, then 0.18/1.18.
  DisplaySettings settings;
  settings.toneOperator = "reinhard";
  settings.transfer = TransferCurve::Gamma;
  settings.gamma = 1;
  EXPECT_NEAR(encodeGrey(42, settings), 0.18 / 1.18, 1e-7);
  settings.parameters.whiteCdM2 = 42;  // the only luminance is the white point
  EXPECT_NEAR(encodeGrey(42, settings), 1.0, 1e-7);
}

TEST(Aces, HillFit) {
  const double grey[3] = {0.18, 0.18, 0.18};
  double out[3];
  acesFitted(grey, out);
  for (double v : out) EXPECT_NEAR(v, 0.1056, 2e-3);  // ACES's middle grey, darker than 0.18
  double previous = -1;
  for (double x = 0; x < 100; x = x * 1.5 + 0.01) {
    const double in[3] = {x, x, x};
    acesFitted(in, out);
    EXPECT_GE(out[1], previous);
    EXPECT_LE(out[1], 1.0);
    previous = out[1];
  }
  EXPECT_GT(previous, 0.95);
}

// ---- max-reflected ----

/// A Cornell-box-like HDR image in code: walls lit by a top light, falling off
/// away from it, and the light itself (emission of scenes/cornell-box), with
/// the emitter coverage render would write.
Image syntheticBox(double emissionScale) {
  const int size = 48;
  Image image(size, size);
  image.emitterFraction.assign(size_t(size) * size, 0.0f);
  const double emission[3] = {18.387, 13.9873, 6.75357};
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      double rho[3] = {0.73, 0.73, 0.73};
      if (x < 10) rho[0] = 0.63, rho[1] = 0.065, rho[2] = 0.05;         // red wall
      if (x >= size - 10) rho[0] = 0.14, rho[1] = 0.45, rho[2] = 0.09;  // green wall
      double dx = (x - size / 2.0) / size, dy = (y + 4.0) / size;
      double irradianceShare = 0.04 / (1 + 12 * (dx * dx + dy * dy));  // falls off from the light
      bool light = y >= 2 && y < 5 && x >= 18 && x < 30;
      for (int c = 0; c < 3; ++c)
        image.pixel(x, y)[c] = float(emissionScale * (light ? emission[c] : emission[c] * rho[c] * irradianceShare));
      if (light) image.emitterFraction[size_t(y) * size + x] = 1;
    }
  return image;
}

Image scaled(Image image, double factor) {
  for (float &v : image.rgb) v = float(v * factor);
  return image;
}

TEST(MaxReflected, BrightestReflectingPixelJustBelowFullScaleLightsClamp) {
  Image image = syntheticBox(1);
  DisplaySettings settings;
  settings.toneOperator = "max-reflected";
  settings.transfer = TransferCurve::Gamma;
  settings.gamma = 1;
  DisplayMapping mapping(image, settings);
  EXPECT_TRUE(mapping.warnings().empty());
  const std::vector<uint8_t> emitter = emitterPixelMask(image);
  double brightest = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      double v[3];
      mapping.encode(image.pixel(x, y), v);
      if (image.emitterFraction[size_t(y) * image.width + x] > 0) {
        EXPECT_EQ(v[0], 1.0);  // the light saturates
      } else if (!emitter[size_t(y) * image.width + x]) {
        brightest = std::max({brightest, v[0], v[1], v[2]});
      }
    }
  EXPECT_NEAR(brightest, 0.95, 1e-6);
  // Without the coverage channel the light sets the scale, with a warning.
  image.emitterFraction.clear();
  DisplayMapping blind(image, settings);
  EXPECT_EQ(blind.warnings().size(), 1u);
}

// ---- The firefly and the searchlight (Tumblin & Rushmeier 1993, issue 5) ----

struct FireflySearchlight {
  std::vector<uint16_t> firefly, searchlight;
};

FireflySearchlight mapBoth(const std::string &toneOperator, bool autoExposure = false) {
  DisplaySettings settings;
  settings.toneOperator = toneOperator;
  settings.parameters.autoExposure = autoExposure;
  Image base = syntheticBox(1);
  Image dim = scaled(base, 1e-4), bright = scaled(base, 1e4);
  return {DisplayMapping(dim, settings).quantiseImage(dim), DisplayMapping(bright, settings).quantiseImage(bright)};
}

/// Identical but for float rounding of the scaled radiances: at most one code value apart, rarely.
void expectSameImage(const FireflySearchlight &pair) {
  ASSERT_EQ(pair.firefly.size(), pair.searchlight.size());
  size_t differing = 0;
  for (size_t i = 0; i < pair.firefly.size(); ++i) {
    EXPECT_LE(std::abs(int(pair.firefly[i]) - int(pair.searchlight[i])), 1) << i;
    differing += pair.firefly[i] != pair.searchlight[i];
  }
  EXPECT_LE(differing, pair.firefly.size() / 1000);
}

TEST(FireflySearchlight, NormalisingMappingsShowBothAlike) {
  expectSameImage(mapBoth("linear", true));
  expectSameImage(mapBoth("max-reflected"));
  expectSameImage(mapBoth("reinhard"));
  expectSameImage(mapBoth("aces"));
}

TEST(FireflySearchlight, ToneReproductionShowsTheDimRoomDarkAndTheBrightOneBright) {
  // The same image at 10⁻⁴ and 10⁴ times the level: mean 8-bit value of the whole image.
  // Tumblin–Rushmeier with the eq. 11 adaptation keeps the log-average pixel at the display's black
  // level whatever the level (docs/tone-mapping.md), so its bright image is bright only where the
  // surfaces are: the Cornell box render gives means 6.9 and 35; Ward's 7.6 and 175.
  struct Expectation {
    const char *name;
    double darkAtMost, brightAtLeast;
  };
  for (const Expectation &e : {Expectation{"tumblin-rushmeier", 10, 30}, Expectation{"ward", 10, 150}}) {
    SCOPED_TRACE(e.name);
    FireflySearchlight pair = mapBoth(e.name);
    const double dark = mean8Bit(pair.firefly), bright = mean8Bit(pair.searchlight);
    EXPECT_LT(dark, e.darkAtMost);
    EXPECT_GT(bright, e.brightAtLeast);
    EXPECT_GT(bright, 3 * dark);
    std::printf("%s: firefly mean %.1f, searchlight mean %.1f\n", e.name, dark, bright);
  }
}

// ---- Emitter coverage, files ----

TEST(EmitterCoverage, CornellBoxLightIsCoveredAndNothingElse) {
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  RayTracer tracer(scene);
  const int size = 32;
  PinholeCamera camera(scene.camera, size, size);
  std::vector<float> coverage = emitterCoverage(tracer, camera, size, size);
  int full = 0, partial = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      float f = coverage[size_t(y) * size + x];
      EXPECT_GE(f, 0.0f);
      EXPECT_LE(f, 1.0f);
      if (f > 0) {
        EXPECT_LT(y, size / 4) << "a lit pixel away from the ceiling light at " << x << "," << y;
      }
      full += f == 1.0f;
      partial += f > 0 && f < 1;
    }
  EXPECT_GT(full, 0);
  EXPECT_GT(partial, 0);
  EXPECT_LT(full + partial, size * size / 20);
}

TEST(ImageFiles, ExrKeepsEmitterChannelAndQuantityPlainExrStillReads) {
  Image image(3, 2);
  for (size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = 0.25f * float(i);
  image.emitterFraction = {0, 0.25f, 1, 0, 0.0625f, 0};
  image.quantity = "radiance";
  const test::TempDir scratch("display");
  const std::string path = scratch.file("coverage.exr");
  writeImage(image, path);
  Image back = readImage(path);
  EXPECT_EQ(back.rgb, image.rgb);
  EXPECT_EQ(back.emitterFraction, image.emitterFraction);
  EXPECT_EQ(back.quantity, "radiance");
  Image plain(3, 2);
  writeImage(plain, path);
  Image plainBack = readImage(path);
  EXPECT_TRUE(plainBack.emitterFraction.empty());
  EXPECT_TRUE(plainBack.quantity.empty());
}

TEST(ImageFiles, SixteenBitPngRoundTrips) {
  const std::vector<uint16_t> values = {0, 1, 255, 256, 32768, 65535};
  const test::TempDir scratch("display");
  const std::string path = scratch.file("sixteen.png");
  writePng16(values, 2, 1, path);
  int w = 0, h = 0, channels = 0;
  ASSERT_TRUE(stbi_is_16_bit(path.c_str()));
  stbi_us *read = stbi_load_16(path.c_str(), &w, &h, &channels, 3);
  ASSERT_NE(read, nullptr);
  EXPECT_EQ(w, 2);
  EXPECT_EQ(h, 1);
  EXPECT_EQ(channels, 3);
  for (size_t i = 0; i < values.size(); ++i) EXPECT_EQ(read[i], values[i]);
  stbi_image_free(read);
}

// ---- False colour ----

TEST(FalseColour, ScaleEndsAndLegend) {
  unsigned char low[3], high[3];
  turboColour(0, low);
  turboColour(1, high);
  EXPECT_LT(low[0] + low[1] + low[2], 120);  // near black (Turbo starts dark violet)
  EXPECT_GT(high[0], 100);                   // dark red
  EXPECT_LT(high[2], 20);
  Image image(64, 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) image.pixel(x, y)[c] = float(x * 10.0 / kLuminousEfficacy);  // 0 … 630 cd/m²
  FalseColourSettings settings;
  FalseColourImage map = falseColour(image, settings);
  EXPECT_EQ(map.minimum, 0);
  EXPECT_EQ(map.maximum, 1000);  // 630 rounded up to 1, 2 or 5 × 10^k
  EXPECT_EQ(map.width, 64);
  settings.logarithmic = true;
  settings.legend = true;
  map = falseColour(image, settings);
  EXPECT_EQ(map.maximum, 1000);
  EXPECT_EQ(map.minimum, 1);
  EXPECT_GT(map.width, 64);
  settings.minimum = 0;
  settings.maximum = 100;
  EXPECT_THROW(falseColour(image, settings), InputError);  // a log scale needs MIN > 0
}

}  // namespace
}  // namespace radiant
