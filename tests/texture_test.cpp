// Textures (src/texture/, docs/textures.md): loading PNG/JPEG/EXR into linear
// texels, bilinear and trilinear lookups, the element average ρ̄ of C&W
// eq. 9.11 and bump-map gradients, each against a closed-form value.
//
// Test images are written at run time into temp/radiant-texture-test/<pid>: 8-bit
// RGB and grey PNG, 16-bit grey PNG (libpng here: writePng16 writes RGB only),
// 16-bit RGB PNG (writePng16), JPEG (stb_image_write) and EXR (writeExr, and
// a Y-only one through OpenEXR directly).
#include "texture/texture.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <gtest/gtest.h>
#include <png.h>
#include <stb/stb_image_write.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>

#include "io/image.h"
#include "util/error.h"

namespace radiant {
namespace {

using Point = std::array<double, 2>;
using Polygon = std::vector<Point>;

// ---- Files ----

/// temp/radiant-texture-test/<process id>: CTest runs each test as its own
/// process, possibly in parallel with another build's, so each process gets
/// its own folder and removes it when it exits.
std::string testPath(const std::string &name) {
  struct Folder {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / "radiant-texture-test" / std::to_string(::getpid());
    Folder() { std::filesystem::create_directories(path); }
    ~Folder() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Folder folder;
  return (folder.path / name).string();
}

/// A 1-channel PNG of 8 or 16 bits through libpng (stb_image_write has no
/// 16-bit writer and writePng16 writes RGB).
void writeGreyPng(const std::string &path, int width, int height, int bitDepth,
                  const std::function<unsigned(int, int)> &value) {
  std::FILE *out = std::fopen(path.c_str(), "wb");
  ASSERT_NE(out, nullptr) << path;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  std::vector<unsigned char> row(size_t(width) * bitDepth / 8);
  bool ok = setjmp(png_jmpbuf(png)) == 0;
  if (ok) {
    png_init_io(png, out);
    png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), bitDepth, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const unsigned v = value(x, y);
        if (bitDepth == 16) {
          row[2 * size_t(x)] = static_cast<unsigned char>(v >> 8);
          row[2 * size_t(x) + 1] = static_cast<unsigned char>(v & 0xFF);
        } else {
          row[size_t(x)] = static_cast<unsigned char>(v);
        }
      }
      png_write_row(png, row.data());
    }
    png_write_end(png, nullptr);
  }
  png_destroy_write_struct(&png, &info);
  std::fclose(out);
  ASSERT_TRUE(ok) << "libpng failed writing " << path;
}

/// A Y-only OpenEXR image (writeExr writes R, G, B).
void writeGreyExr(const std::string &path, int width, int height, std::vector<float> values) {
  Imf::Header header(width, height);
  header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
  Imf::OutputFile file(path.c_str(), header);
  Imf::FrameBuffer frame;
  frame.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char *>(values.data()), sizeof(float),
                               sizeof(float) * size_t(width)));
  file.setFrameBuffer(frame);
  file.writePixels(height);
}

/// The texel in column i, row j (row 0 = the file's top row), read back at its centre.
Bands texelAt(const Texture &texture, int i, int j) {
  return texture.bilinear((i + 0.5) / texture.width(), 1 - (j + 0.5) / texture.height());
}

double srgbDecode(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

/// Load must throw InputError located at `path` whose message contains `fragment`.
void expectLoadError(const std::string &path, const std::string &fragment) {
  try {
    Texture::load(path, TextureEncoding::Colour);
    ADD_FAILURE() << "loading " << path << " did not throw";
  } catch (const InputError &e) {
    EXPECT_EQ(e.location().file, path);
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

/// 8-bit codes of a 5 × 3 RGB test image, distinct per texel and band; the
/// top-left texel (file row 0) is grey 128.
std::vector<unsigned char> codes5x3() {
  std::vector<unsigned char> codes(5 * 3 * 3);
  for (size_t k = 0; k < codes.size(); ++k) codes[k] = static_cast<unsigned char>((k * 37 + 11) % 256);
  codes[0] = codes[1] = codes[2] = 128;
  return codes;
}

// ---- Loading ----

TEST(Texture, EightBitPngIsSrgbDecodedForColourAndRawForData) {
  const std::string path = testPath("rgb8.png");
  const auto codes = codes5x3();
  writePngBytes(codes, 5, 3, path);
  const Texture colour = Texture::load(path, TextureEncoding::Colour);
  const Texture data = Texture::load(path, TextureEncoding::Data);
  ASSERT_EQ(colour.width(), 5);
  ASSERT_EQ(colour.height(), 3);
  // IEC 61966-2-1 decode: code 128 → V = 128/255 →
  // ((V + 0.055)/1.055)^2.4 = 0.2158605.
  EXPECT_NEAR(texelAt(colour, 0, 0)[0], 0.2158605, 1e-6);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 5; ++i)
      for (int b = 0; b < 3; ++b) {
        const double v = codes[(size_t(j) * 5 + i) * 3 + b] / 255.0;
        EXPECT_NEAR(texelAt(colour, i, j)[b], srgbDecode(v), 1e-7);  // float storage
        EXPECT_NEAR(texelAt(data, i, j)[b], v, 1e-7);
      }
}

TEST(Texture, FileTopRowIsVOne) {
  // 7 × 1 would not tell rows apart: a 2 × 3 grey image with one bright corner.
  const std::string path = testPath("corner.png");
  writeGreyPng(path, 2, 3, 8, [](int x, int y) { return x == 0 && y == 0 ? 255u : (x == 1 && y == 2 ? 51u : 0u); });
  const Texture t = Texture::load(path, TextureEncoding::Data);
  // The file's top-left texel sits at the top-left of texture space: u small, v near 1.
  EXPECT_NEAR(t.bilinear(0.25, 1 - 1.0 / 6)[0], 1.0, 1e-7);
  EXPECT_NEAR(t.bilinear(0.25, 1.0 / 6)[0], 0.0, 1e-7);
  // Its bottom-right texel at u near 1, v near 0.
  EXPECT_NEAR(t.bilinear(0.75, 1.0 / 6)[0], 0.2, 1e-7);
  EXPECT_NEAR(t.bilinear(0.75, 1 - 1.0 / 6)[0], 0.0, 1e-7);
}

TEST(Texture, GreyPngFillsAllBands) {
  const std::string path = testPath("grey8.png");
  writeGreyPng(path, 7, 1, 8, [](int x, int) { return unsigned(x * 40); });
  const Texture t = Texture::load(path, TextureEncoding::Colour);
  ASSERT_EQ(t.width(), 7);
  ASSERT_EQ(t.height(), 1);
  for (int i = 0; i < 7; ++i) {
    const Bands b = texelAt(t, i, 0);
    EXPECT_NEAR(b[0], srgbDecode(i * 40 / 255.0), 1e-7);
    EXPECT_EQ(b[0], b[1]);
    EXPECT_EQ(b[0], b[2]);
  }
}

TEST(Texture, SixteenBitGreyPngKeepsEverySixteenBitCode) {
  // Codes that 8 bits cannot tell apart (0 and 1, 65534 and 65535): the
  // 16-bit path must keep them, to float precision (≤ 3e-8 ≪ 1/65535 = 1.5e-5).
  const std::vector<unsigned> codes = {0, 1, 257, 32768, 40000, 65534, 65535};
  const std::string path = testPath("grey16.png");
  writeGreyPng(path, 7, 1, 16, [&](int x, int) { return codes[size_t(x)]; });
  const Texture data = Texture::load(path, TextureEncoding::Data);
  const Texture colour = Texture::load(path, TextureEncoding::Colour);
  for (int i = 0; i < 7; ++i) {
    EXPECT_NEAR(texelAt(data, i, 0)[1], codes[size_t(i)] / 65535.0, 3e-8) << i;
    EXPECT_NEAR(texelAt(colour, i, 0)[2], srgbDecode(codes[size_t(i)] / 65535.0), 3e-8) << i;
  }
  EXPECT_GT(texelAt(data, 1, 0)[0], 0.0);
  EXPECT_LT(texelAt(data, 5, 0)[0], texelAt(data, 6, 0)[0]);
}

TEST(Texture, SixteenBitRgbPngIsExact) {
  std::vector<uint16_t> codes(5 * 3 * 3);
  for (size_t k = 0; k < codes.size(); ++k) codes[k] = static_cast<uint16_t>((k * 4099 + 1) % 65536);
  const std::string path = testPath("rgb16.png");
  writePng16(codes, 5, 3, path);
  const Texture t = Texture::load(path, TextureEncoding::Data);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 5; ++i)
      for (int b = 0; b < 3; ++b) EXPECT_NEAR(texelAt(t, i, j)[b], codes[(size_t(j) * 5 + i) * 3 + b] / 65535.0, 3e-8);
}

TEST(Texture, JpegWithinItsQuantisationError) {
  // A smooth 5 × 3 image at quality 100 (stb writes 4:4:4 above 90): the only
  // loss is rounding in the DCT and in YCbCr, 2 codes measured. Tolerance 4/255.
  std::vector<unsigned char> codes(5 * 3 * 3);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 5; ++i) {
      unsigned char *p = &codes[(size_t(j) * 5 + i) * 3];
      p[0] = static_cast<unsigned char>(60 + 20 * i);
      p[1] = static_cast<unsigned char>(100 + 30 * j);
      p[2] = static_cast<unsigned char>(180 - 10 * i - 10 * j);
    }
  const std::string path = testPath("smooth.jpg");
  ASSERT_TRUE(stbi_write_jpg(path.c_str(), 5, 3, 3, codes.data(), 100));
  const Texture t = Texture::load(path, TextureEncoding::Data);
  ASSERT_EQ(t.width(), 5);
  ASSERT_EQ(t.height(), 3);
  double worst = 0;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 5; ++i)
      for (int b = 0; b < 3; ++b)
        worst = std::max(worst, std::abs(texelAt(t, i, j)[b] - codes[(size_t(j) * 5 + i) * 3 + b] / 255.0));
  EXPECT_LE(worst, 4.0 / 255) << "worst JPEG error " << worst * 255 << " codes";
}

// EXR is linear for both encodings (never sRGB-decoded). Data keeps HDR
// values; a colour texture is a reflectance, so its values are clamped to [0, 1].
TEST(Texture, ExrIsLinearAndExactForBothEncodings) {
  Image image(5, 3);
  for (size_t k = 0; k < image.rgb.size(); ++k) image.rgb[k] = float(0.001 + 0.37 * double(k));  // up to 16: HDR
  const std::string path = testPath("linear.exr");
  writeExr(image, path);
  for (TextureEncoding encoding : {TextureEncoding::Colour, TextureEncoding::Data}) {
    const Texture t = Texture::load(path, encoding);
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 5; ++i)
        for (int b = 0; b < 3; ++b) {
          const double stored = image.pixel(i, j)[b];
          EXPECT_NEAR(texelAt(t, i, j)[b], encoding == TextureEncoding::Colour ? std::min(stored, 1.0) : stored, 1e-12);
        }
  }
}

TEST(Texture, GreyExrFillsAllBands) {
  const std::string path = testPath("grey.exr");
  writeGreyExr(path, 1, 1, {0.625f});
  const Texture t = Texture::load(path, TextureEncoding::Colour);
  ASSERT_EQ(t.width(), 1);
  EXPECT_EQ(t.mean()[0], 0.625);
  EXPECT_EQ(t.mean()[1], 0.625);
  EXPECT_EQ(t.mean()[2], 0.625);
}

TEST(Texture, MissingFileIsAnInputError) {
  expectLoadError(testPath("does-not-exist.png"), "no such file");
}

TEST(Texture, TextFileNamedPngIsAnInputError) {
  const std::string path = testPath("text.png");
  std::ofstream(path) << "this is not an image\n";
  expectLoadError(path, "not an image");
}

TEST(Texture, EmptyFileIsAnInputError) {
  const std::string path = testPath("empty.png");
  std::ofstream(path).close();
  expectLoadError(path, "empty");
}

TEST(Texture, TruncatedPngIsAnInputError) {
  const std::string path = testPath("truncated.png");
  std::mt19937 random(7);
  writeGreyPng(path, 64, 64, 8, [&](int, int) { return unsigned(random() % 256); });  // noise: no compression
  std::filesystem::resize_file(path, std::filesystem::file_size(path) / 2);
  expectLoadError(path, "cannot decode");
}

TEST(Texture, TooLargeFileIsRefusedBeforeDecoding) {
  // 4097 × 4096 zeros: a few kB of PNG, one column over the limit of 2^24.
  const std::string path = testPath("too-large.png");
  writeGreyPng(path, 4097, 4096, 8, [](int, int) { return 0u; });
  expectLoadError(path, "4097x4096");
  expectLoadError(path, "16777216");
}

TEST(Texture, TooLargeExrIsRefusedFromItsHeader) {
  // A header claiming 4097 × 4096 and no pixels: the limit must be checked on
  // the data window, before anything of that size is allocated or read.
  const std::string path = testPath("too-large.exr");
  {
    Imf::Header header(4097, 4096);
    header.channels().insert("Y", Imf::Channel(Imf::HALF));
    Imf::OutputFile file(path.c_str(), header);
  }
  expectLoadError(path, "4097x4096");
}

TEST(Texture, AlphaIsIgnored) {
  const std::string path = testPath("rgba.png");
  const std::vector<unsigned char> rgba = {255, 0, 51, 0, 255, 0, 51, 255};
  ASSERT_TRUE(stbi_write_png(path.c_str(), 2, 1, 4, rgba.data(), 8));
  const Texture t = Texture::load(path, TextureEncoding::Data);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(texelAt(t, i, 0)[0], 1.0, 1e-7);
    EXPECT_NEAR(texelAt(t, i, 0)[1], 0.0, 1e-7);
    EXPECT_NEAR(texelAt(t, i, 0)[2], 0.2, 1e-7);
  }
}

TEST(Texture, ConstructorRefusesMismatchedSizes) {
  EXPECT_THROW(Texture(0, 1, {}), std::invalid_argument);
  EXPECT_THROW(Texture(2, 2, std::vector<Bands>(3)), std::invalid_argument);
}

TEST(Texture, DirectoryIsAnInputError) {
  const std::string path = testPath("a-directory.png");
  std::filesystem::create_directories(path);
  expectLoadError(path, "not a regular file");
}

// ---- Bilinear ----

/// Texels on a 1/64 grid, exact in float, so lookups compare to rounding only.
std::vector<Bands> gridTexels(int width, int height, unsigned seed) {
  std::mt19937 random(seed);
  std::vector<Bands> texels(size_t(width) * height);
  for (Bands &t : texels) t = Bands(random() % 65 / 64.0, random() % 65 / 64.0, random() % 65 / 64.0);
  return texels;
}

TEST(Texture, BilinearIsExactAtTexelCentres) {
  const auto texels = gridTexels(5, 3, 1);
  for (TextureWrap wrap : {TextureWrap::Repeat, TextureWrap::Clamp}) {
    const Texture t(5, 3, texels, wrap);
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 5; ++i)
        for (int b = 0; b < 3; ++b) EXPECT_NEAR(texelAt(t, i, j)[b], texels[size_t(j) * 5 + i][b], 1e-14);
  }
}

TEST(Texture, BilinearIsLinearBetweenTwoTexels) {
  const Texture across(2, 1, {Bands(0.25), Bands(0.75)});
  const Texture down(1, 2, {Bands(0.25), Bands(0.75)});  // row 0 (v = 3/4) is 0.25
  for (double s = 0.25; s <= 0.75; s += 0.03125) {
    EXPECT_NEAR(across.bilinear(s, 0.3)[0], 0.25 + (s - 0.25), 1e-14);  // slope 0.5 per 0.5 of u
    EXPECT_NEAR(down.bilinear(0.3, s)[0], 0.75 - (s - 0.25), 1e-14);
  }
}

TEST(Texture, RepeatWrapsAcrossTheSeamAndClampDoesNot) {
  const std::vector<Bands> texels = {Bands(1), Bands(0), Bands(0), Bands(0.5)};
  const Texture repeat(4, 1, texels, TextureWrap::Repeat);
  const Texture clamp(4, 1, texels, TextureWrap::Clamp);
  // u = 0 lies halfway between the last column's centre (at −1/8) and the first's (1/8).
  EXPECT_NEAR(repeat.bilinear(0, 0.5)[0], 0.75, 1e-14);
  EXPECT_NEAR(repeat.bilinear(1, 0.5)[0], 0.75, 1e-14);
  EXPECT_NEAR(repeat.bilinear(-0.125, 0.5)[0], 0.5, 1e-14);
  EXPECT_NEAR(repeat.bilinear(3.125, 7.5)[0], 1.0, 1e-14);
  EXPECT_NEAR(clamp.bilinear(0, 0.5)[0], 1.0, 1e-14);
  EXPECT_NEAR(clamp.bilinear(1, 0.5)[0], 0.5, 1e-14);
  EXPECT_NEAR(clamp.bilinear(-3, 0.5)[0], 1.0, 1e-14);
  EXPECT_NEAR(clamp.bilinear(2, -4)[0], 0.5, 1e-14);
}

// ---- Filtered ----

std::vector<Bands> checkerboard(int width, int height) {
  std::vector<Bands> texels(size_t(width) * height);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) texels[size_t(j) * width + i] = Bands((i + j) % 2 ? 1.0 : 0.0);
  return texels;
}

TEST(Texture, FilteredWithFootprintBelowOneTexelIsBilinear) {
  const Texture t(7, 5, gridTexels(7, 5, 2));
  for (double u = -0.3; u < 1.3; u += 0.0731)
    for (double v = -0.2; v < 1.2; v += 0.0917)
      for (double footprint : {0.0, 0.5 / 7, 1.0 / 7}) EXPECT_EQ(t.filtered(u, v, footprint)[0], t.bilinear(u, v)[0]);
}

TEST(Texture, FilteredWithWholeTextureFootprintIsTheMean) {
  const Texture t(7, 5, gridTexels(7, 5, 3), TextureWrap::Clamp);
  for (double footprint : {1.0, 10.0, 1e300})
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(t.filtered(0.3, 0.8, footprint)[b], t.mean()[b], 1e-6);  // float pyramid
}

TEST(Texture, FilteredCheckerboardAtFourTexelsIsHalf) {
  // 1-texel squares: point lookups give 0 or 1; from level 1 on every texel
  // is the mean of whole 2 × 2 blocks, exactly 0.5 in float.
  const Texture t(64, 64, checkerboard(64, 64));
  EXPECT_NEAR(t.filtered(0.5 / 64, 0.5 / 64, 0)[0], 1.0, 1e-12);
  for (double footprint : {3.0 / 64, 4.0 / 64, 5.5 / 64})
    for (double u = 0.01; u < 1; u += 0.097) EXPECT_NEAR(t.filtered(u, 1 - u * 0.7, footprint)[0], 0.5, 1e-7);
  // An odd size has no exact 2 × 2 blocks. Footprint 4/63 blends levels 2
  // and 3, whose texels are s = 63/16 and 63/8 fine texels wide: 1/16 and 1/8
  // short of an even count. Along one axis the ±1 square wave then sums to at
  // most that shortfall, |A| ≤ (1/16)/s = 0.016, and a texel of the checkerboard
  // ½(1 − (−1)^(i+j)) is ½ − ½·Aᵤ·Aᵥ: within ½·0.016² = 1.3e-4 of 0.5.
  const Texture odd(63, 63, checkerboard(63, 63));
  for (double u = 0.01; u < 1; u += 0.097) EXPECT_NEAR(odd.filtered(u, 1 - u * 0.7, 4.0 / 63)[0], 0.5, 1.3e-4);
}

/// Level sizes as texture.h documents them: halved, rounded up, to 1 × 1.
std::vector<std::array<int, 2>> levelSizes(int width, int height) {
  std::vector<std::array<int, 2>> sizes = {{width, height}};
  while (sizes.back()[0] > 1 || sizes.back()[1] > 1)
    sizes.push_back({(sizes.back()[0] + 1) / 2, (sizes.back()[1] + 1) / 2});
  return sizes;
}

TEST(Texture, PyramidOfOddSizesKeepsTheMean) {
  // filtered() at a footprint of exactly one texel of level L is level L,
  // unblended; read at that level's texel centres it returns its texels.
  for (auto [width, height] : std::vector<std::array<int, 2>>{{5, 3}, {7, 1}, {1, 7}, {13, 11}, {1, 1}, {33, 2}}) {
    const Texture t(width, height, gridTexels(width, height, unsigned(width * 100 + height)));
    for (auto [w, h] : levelSizes(width, height)) {
      const double footprint = 1.0 / std::max(w, h);
      Bands sum;
      for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) sum += t.filtered((i + 0.5) / w, 1 - (j + 0.5) / h, footprint);
      for (int b = 0; b < 3; ++b)
        EXPECT_NEAR(sum[b] / (w * h), t.mean()[b], 1e-6) << width << "x" << height << " level " << w << "x" << h;
    }
  }
}

// ---- Average ----

Polygon rectangle(double u0, double v0, double u1, double v1) {
  return {{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}};
}

double polygonArea(const Polygon &p) {
  double a = 0;
  for (size_t k = 0; k < p.size(); ++k) a += p[k][0] * p[(k + 1) % p.size()][1] - p[(k + 1) % p.size()][0] * p[k][1];
  return a / 2;
}

/// Midpoint rule on an n × n grid over the bounding box of a convex polygon:
/// an independent reference for average(). Its error is the boundary cells'
/// share, about perimeter/(n·side) of the range.
Bands denseAverage(const Texture &t, const Polygon &p, int n) {
  double u0 = p[0][0], u1 = u0, v0 = p[0][1], v1 = v0;
  for (const Point &q : p)
    u0 = std::min(u0, q[0]), u1 = std::max(u1, q[0]), v0 = std::min(v0, q[1]), v1 = std::max(v1, q[1]);
  const double sign = polygonArea(p) > 0 ? 1 : -1;
  Bands sum;
  int count = 0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const double u = u0 + (a + 0.5) / n * (u1 - u0), v = v0 + (b + 0.5) / n * (v1 - v0);
      bool inside = true;
      for (size_t k = 0; k < p.size() && inside; ++k) {
        const Point &e0 = p[k], &e1 = p[(k + 1) % p.size()];
        inside = sign * ((e1[0] - e0[0]) * (v - e0[1]) - (e1[1] - e0[1]) * (u - e0[0])) >= 0;
      }
      if (inside) sum += t.bilinear(u, v), ++count;
    }
  return sum / count;
}

TEST(Texture, AverageOfAConstantIsTheConstant) {
  const std::vector<Bands> texels(15, Bands(0.375, 0.125, 0.75));
  const std::vector<Polygon> polygons = {
      {{0.41, 0.43}, {0.42, 0.43}, {0.41, 0.44}},  // inside one cell
      rectangle(0.1, 0.2, 0.9, 0.7),
      {{-0.3, -0.2}, {1.7, 0.1}, {0.4, 2.3}},  // over the edges and seams
      rectangle(0.2, 0.7, -0.4, -0.6),         // clockwise
  };
  for (TextureWrap wrap : {TextureWrap::Repeat, TextureWrap::Clamp}) {
    const Texture t(5, 3, texels, wrap);
    for (const Polygon &p : polygons)
      for (int b = 0; b < 3; ++b) EXPECT_NEAR(t.average(p)[b], texels[0][b], 1e-14);  // rounding only
  }
}

TEST(Texture, AverageOverTheWholeSquareIsTheMean) {
  // The bilinear reconstruction of any level integrates over [0, 1]² to that
  // level's mean under both wrap modes (Clamp's flat half-texel borders
  // exactly replace the tents' missing halves). 5 × 3 is integrated on the
  // finest level, exact to rounding; 256 × 256 meets more than the cell cap
  // and runs on a coarser level, exact to the pyramid's float rounding.
  for (auto [width, height] : std::vector<std::array<int, 2>>{{5, 3}, {256, 256}}) {
    const double tolerance = width == 5 ? 1e-14 : 1e-6;
    for (TextureWrap wrap : {TextureWrap::Repeat, TextureWrap::Clamp}) {
      const Texture t(width, height, gridTexels(width, height, 4), wrap);
      for (const Polygon &p : {rectangle(0, 0, 1, 1), rectangle(1, 0, 0, 1)})
        for (int b = 0; b < 3; ++b) EXPECT_NEAR(t.average(p)[b], t.mean()[b], tolerance);
    }
  }
}

TEST(Texture, CheckerboardOverWholePeriodsIsHalf) {
  // 8 × 8 one-texel squares: the period lattice is spanned by (2, 0) and
  // (1, 1) texels. A polygon tiled by it integrates to exactly 0.5 of its area.
  const Texture t(8, 8, checkerboard(8, 8));
  EXPECT_NEAR(t.average(rectangle(0.125, 0.25, 0.625, 0.75))[0], 0.5, 1e-14);
  EXPECT_NEAR(t.average(rectangle(0.3, 0.1, 0.55, 0.35))[0], 0.5, 1e-14);  // offset by a fraction of a texel
  // Parallelogram with sides (4, 0) and (2, 4) texels: lattice vectors.
  EXPECT_NEAR(t.average(Polygon{{0.1, 0.2}, {0.6, 0.2}, {0.85, 0.7}, {0.35, 0.7}})[0], 0.5, 1e-14);
}

TEST(Texture, HalfSquareOfHalfLitTextureMatchesTheIntegral) {
  // 1 for u < 1/2, 0 beyond, Clamp (no seam blend at u = 0). Over the triangle
  // (0,0), (1,0), (0,1) of area 1/2, the part with u < 1/2 has area
  // ∫₀^½ (1 − u) du = 3/8, so a sharp step averages 3/4. The bilinear
  // reconstruction ramps from 1 to 0 over δ = 1/(2w) either side of u = 1/2,
  // which moves ∫ f·(1 − u) du by −δ²/6: the exact value is 3/4 − 1/(12 w²).
  for (int width : {8, 64}) {
    std::vector<Bands> texels(size_t(width) * 4);
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < width; ++i) texels[size_t(j) * width + i] = Bands(i < width / 2 ? 1.0 : 0.0);
    const Texture t(width, 4, texels, TextureWrap::Clamp);
    const Polygon half = {{0, 0}, {1, 0}, {0, 1}};
    const double exact = 0.75 - 1.0 / (12.0 * width * width);
    EXPECT_NEAR(t.average(half)[0], exact, 1e-14) << width;
    EXPECT_NEAR(t.average(half)[0], 0.75, 1.0 / (12.0 * width * width) + 1e-14);
    EXPECT_NEAR(denseAverage(t, half, 1000)[0], exact, 2e-3);  // independent check of the closed form
    // One sample at the centroid (1/3, 1/3) would read 1: the average must not.
    EXPECT_NEAR(t.bilinear(1.0 / 3, 1.0 / 3)[0], 1.0, 1e-14);
    EXPECT_GT(std::abs(t.average(half)[0] - t.bilinear(1.0 / 3, 1.0 / 3)[0]), 0.2);
  }
}

TEST(Texture, RepeatAverageAcrossTheSeamIsThePeriodMean) {
  // [0.5, 1.5] × [0, 1] is one whole period shifted by half: the mean.
  const Texture repeat(2, 3, {Bands(0.2), Bands(0.9), Bands(0.4), Bands(0.1), Bands(0.6), Bands(0.7)});
  EXPECT_NEAR(repeat.average(rectangle(0.5, 0, 1.5, 1))[0], repeat.mean()[0], 1e-14);
  EXPECT_NEAR(repeat.average(rectangle(-7.5, 3, -6.5, 4))[0], repeat.mean()[0], 1e-14);
}

TEST(Texture, AverageAgreesWithDenseSampling) {
  // Polygons from a fraction of a texel to several texels, across the seam
  // and (Clamp) beyond the square; texels span [0, 1]. average() is exact, so
  // the difference is the reference's: a midpoint rule on 600² points, whose
  // boundary error is ~ perimeter/(600·side) of the variation inside the
  // polygon (measured 1.7e-5 at worst). Tolerance 2e-4.
  const std::vector<Polygon> polygons = {
      {{0.401, 0.333}, {0.43, 0.35}, {0.405, 0.37}},             // ~1/4 of a texel
      {{0.12, 0.08}, {0.61, 0.21}, {0.52, 0.74}, {0.18, 0.55}},  // many texels
      {{-0.15, 0.4}, {0.2, 0.35}, {0.1, 0.9}},                   // across u = 0
      {{0.7, 0.8}, {1.3, 0.9}, {1.1, 1.4}, {0.8, 1.2}},          // across the corner
  };
  double worst = 0;
  for (TextureWrap wrap : {TextureWrap::Repeat, TextureWrap::Clamp}) {
    const Texture t(13, 11, gridTexels(13, 11, 5), wrap);
    for (const Polygon &p : polygons) {
      const Bands exact = t.average(p), reference = denseAverage(t, p, 600);
      for (int b = 0; b < 3; ++b) {
        EXPECT_NEAR(exact[b], reference[b], 2e-4);
        worst = std::max(worst, std::abs(exact[b] - reference[b]));
      }
    }
  }
  std::cout << "average vs dense sampling: worst difference " << worst << "\n";
}

/// The part of p inside [u0, u1] × [v0, v1] (Sutherland–Hodgman).
Polygon clipToRectangle(Polygon p, double u0, double v0, double u1, double v1) {
  const std::array<std::array<double, 3>, 4> planes = {{{0, u0, 1}, {0, u1, -1}, {1, v0, 1}, {1, v1, -1}}};
  for (const auto &plane : planes) {
    const int axis = int(plane[0]);
    Polygon out;
    for (size_t k = 0; k < p.size(); ++k) {
      const Point &a = p[k], &b = p[(k + 1) % p.size()];
      const double da = plane[2] * (a[axis] - plane[1]), db = plane[2] * (b[axis] - plane[1]);
      if (da >= 0) out.push_back(a);
      if ((da >= 0) != (db >= 0)) {
        const double s = da / (da - db);
        out.push_back({a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])});
      }
    }
    p = out;
    if (p.empty()) break;
  }
  return p;
}

/// The finest-level average of a large polygon: the area-weighted sum over its
/// parts in a 32 × 32 grid of squares, each small enough for level 0.
Bands finestLevelAverage(const Texture &t, const Polygon &p) {
  Bands sum;
  double area = 0;
  for (int a = 0; a < 32; ++a)
    for (int b = 0; b < 32; ++b) {
      const Polygon piece = clipToRectangle(p, a / 32.0, b / 32.0, (a + 1) / 32.0, (b + 1) / 32.0);
      if (piece.size() < 3 || std::abs(polygonArea(piece)) < 1e-14) continue;
      sum += std::abs(polygonArea(piece)) * t.average(piece);
      area += std::abs(polygonArea(piece));
    }
  return sum / area;
}

TEST(Texture, LargePolygonsOnCoarseLevelsStayAccurate) {
  // 512 × 512 and a tilted quad over most of it: ~2·10⁵ texels, above the
  // cell cap, so average() integrates a coarser level. Its error is confined
  // to the cells the boundary crosses; measured against the finest level:
  // a sharp edge crossing the boundary ≤ 1e-3 of the range, noise and
  // checkerboards far less.
  const int n = 512;
  std::vector<Bands> step(size_t(n) * n), noise(size_t(n) * n);
  std::mt19937 random(9);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      step[size_t(j) * n + i] = Bands(i + 0.3 * j < 0.6 * n ? 1.0 : 0.0);
      noise[size_t(j) * n + i] = Bands(random() % 1024 / 1023.0);
    }
  const Polygon quad = {{0.03, 0.11}, {0.93, 0.02}, {0.97, 0.89}, {0.08, 0.96}};
  for (const auto &texels : {step, noise, checkerboard(n, n)}) {
    const Texture t(n, n, texels);
    const double error = std::abs(t.average(quad)[0] - finestLevelAverage(t, quad)[0]);
    EXPECT_LE(error, 1e-3);
    std::cout << "coarse-level average error: " << error << "\n";
  }
}

TEST(Texture, ZeroAreaPolygonGivesBilinearAtItsFirstVertex) {
  const Texture t(5, 3, gridTexels(5, 3, 6));
  const Polygon segment = {{0.37, 0.41}, {0.8, 0.9}, {0.585, 0.655}};  // third vertex halfway along
  for (int b = 0; b < 3; ++b) EXPECT_NEAR(t.average(segment)[b], t.bilinear(0.37, 0.41)[b], 1e-14);
  EXPECT_EQ(t.average(Polygon{{0.21, 0.77}})[0], t.bilinear(0.21, 0.77)[0]);
  EXPECT_EQ(t.average(Polygon{{0.21, 0.77}, {0.6, 0.1}})[0], t.bilinear(0.21, 0.77)[0]);
}

// ---- Gradient ----

TEST(Texture, GradientOfALinearRampIsOne) {
  // Texels (i + 0.5)/8 are exact in float, so the slope is exact: h = u.
  std::vector<Bands> ramp(8 * 3);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 8; ++i) ramp[size_t(j) * 8 + i] = Bands((i + 0.5) / 8);
  for (TextureWrap wrap : {TextureWrap::Repeat, TextureWrap::Clamp}) {
    const Texture t(8, 3, ramp, wrap);
    for (double u = 0.5 / 8; u < 7.5 / 8; u += 0.0371)
      for (double v = 0.05; v < 1; v += 0.13) {
        const auto g = t.gradient(u, v);
        EXPECT_NEAR(g[0], 1.0, 1e-9);
        EXPECT_NEAR(g[1], 0.0, 1e-9);
      }
  }
}

TEST(Texture, GradientOfAConstantIsZero) {
  const Texture t(5, 3, std::vector<Bands>(15, Bands(0.3)));
  for (double u = -0.5; u < 1.5; u += 0.173) {
    const auto g = t.gradient(u, 1 - u);
    EXPECT_EQ(g[0], 0.0);
    EXPECT_EQ(g[1], 0.0);
  }
}

TEST(Texture, GradientPointsUpInV) {
  // Row 0 is the top (v = 1): texels 1 − (j + 0.5)/8 make h = v, slope +1 in v.
  std::vector<Bands> ramp(3 * 8);
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 3; ++i) ramp[size_t(j) * 3 + i] = Bands(1 - (j + 0.5) / 8);
  const Texture t(3, 8, ramp, TextureWrap::Clamp);
  // Strictly between the outermost centres: at a centre the slope is one-sided.
  for (double v = 0.6 / 8; v < 7.5 / 8; v += 0.0413) {
    const auto g = t.gradient(0.4, v);
    EXPECT_NEAR(g[0], 0.0, 1e-9);
    EXPECT_NEAR(g[1], 1.0, 1e-9);
  }
  // Mean of the bands: a ramp in one band only has a third of the slope.
  std::vector<Bands> red(3 * 8);
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 3; ++i) red[size_t(j) * 3 + i] = Bands(1 - (j + 0.5) / 8, 0, 0);
  EXPECT_NEAR(Texture(3, 8, red).gradient(0.4, 0.5)[1], 1.0 / 3, 1e-9);
}

}  // namespace
}  // namespace radiant
