// Writes the image seeds of the texture and image fuzz targets: small files
// of every kind the readers take, so that the fuzzer starts inside each
// decoder instead of having to discover its signature and header.
//
//   fuzz_make_seeds CORPUS   (CORPUS: fuzz/corpus; tools/fuzz.sh --seeds runs it)
//
// texture/: PNG 8-bit grey, grey + alpha, RGB, RGBA (stb_image_write), 16-bit
// RGB (libpng, writePng16), JPEG grey and RGB (stb_image_write), OpenEXR
// float RGB, half Y, RGB with each of OpenEXR's common compressions, a tiled
// one and one whose data window is away from (0, 0). image/: the same EXRs,
// two written by writeExr (the emitter channel and the quantity attribute,
// and spectral channels), PFM colour and grey, either byte order. Every image is a few texels: decoding stays fast,
// input after input.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfTiledOutputFile.h>
#include <stb/stb_image_write.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "io/image.h"

namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 5, kHeight = 3;

std::vector<unsigned char> codes(int channels) {
  std::vector<unsigned char> out;
  for (int i = 0; i < kWidth * kHeight * channels; ++i) out.push_back(static_cast<unsigned char>(i * 37 % 256));
  return out;
}

void writeExrFile(const std::string &path, bool grey, Imf::PixelType type, Imf::Compression compression, bool tiled,
                  int originX, int originY) {
  // A data window away from (0, 0): the readers address their buffers from its corner.
  const Imath::Box2i window({originX, originY}, {originX + kWidth - 1, originY + kHeight - 1});
  Imf::Header header(window, window);
  header.compression() = compression;
  std::vector<std::string> names = grey ? std::vector<std::string>{"Y"} : std::vector<std::string>{"R", "G", "B"};
  for (const std::string &name : names) header.channels().insert(name, Imf::Channel(type));
  std::vector<float> floats(size_t(kWidth) * kHeight * names.size());
  std::vector<Imath::half> halves(floats.size());
  for (size_t i = 0; i < floats.size(); ++i) floats[i] = halves[i] = float(i) / float(floats.size());
  const size_t size = type == Imf::HALF ? sizeof(Imath::half) : sizeof(float);
  char *base = (type == Imf::HALF ? reinterpret_cast<char *>(halves.data()) : reinterpret_cast<char *>(floats.data())) -
               (ptrdiff_t(originX) + ptrdiff_t(originY) * kWidth) * ptrdiff_t(names.size() * size);
  Imf::FrameBuffer frame;
  for (size_t c = 0; c < names.size(); ++c)
    frame.insert(names[c], Imf::Slice(type, base + c * size, names.size() * size, names.size() * size * kWidth));
  if (tiled) {
    header.setTileDescription(Imf::TileDescription(2, 2, Imf::ONE_LEVEL));
    Imf::TiledOutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writeTiles(0, file.numXTiles() - 1, 0, file.numYTiles() - 1);
  } else {
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(kHeight);
  }
}

void writePfmFile(const std::string &path, bool colour, bool bigEndian) {
  const int channels = colour ? 3 : 1;
  std::ofstream out(path, std::ios::binary);
  out << (colour ? "PF" : "Pf") << "\n" << kWidth << " " << kHeight << "\n" << (bigEndian ? "1.0" : "-1.0") << "\n";
  for (int i = 0; i < kWidth * kHeight * channels; ++i) {
    float value = float(i) / 7.0f;
    unsigned char bytes[4];
    std::memcpy(bytes, &value, 4);
    if (bigEndian) std::swap(bytes[0], bytes[3]), std::swap(bytes[1], bytes[2]);
    out.write(reinterpret_cast<const char *>(bytes), 4);
  }
}

}  // namespace

int main(int argc, char **argv) {
  if (argc != 2) {
    std::cerr << "usage: fuzz_make_seeds CORPUS_FOLDER (fuzz/corpus)\n";
    return 2;
  }
  const fs::path texture = fs::path(argv[1]) / "texture", image = fs::path(argv[1]) / "image";
  fs::create_directories(texture);
  fs::create_directories(image);
  auto at = [](const fs::path &folder, const char *name) { return (folder / name).string(); };

  const char *pngNames[] = {"", "grey.png", "grey-alpha.png", "rgb.png", "rgba.png"};
  for (int channels = 1; channels <= 4; ++channels)
    stbi_write_png(at(texture, pngNames[channels]).c_str(), kWidth, kHeight, channels, codes(channels).data(),
                   kWidth * channels);
  std::vector<uint16_t> rgb16;
  for (int i = 0; i < kWidth * kHeight * 3; ++i) rgb16.push_back(static_cast<uint16_t>(i * 4099));
  radiant::writePng16(rgb16, kWidth, kHeight, at(texture, "rgb16.png"));
  stbi_write_jpg(at(texture, "grey.jpg").c_str(), kWidth, kHeight, 1, codes(1).data(), 90);
  stbi_write_jpg(at(texture, "rgb.jpg").c_str(), kWidth, kHeight, 3, codes(3).data(), 90);

  struct ExrSeed {
    const char *name;
    bool grey;
    Imf::PixelType type;
    Imf::Compression compression;
    bool tiled;
    int originX = 0, originY = 0;
  };
  const ExrSeed exrSeeds[] = {
      {"rgb-float.exr", false, Imf::FLOAT, Imf::NO_COMPRESSION, false},
      {"y-half.exr", true, Imf::HALF, Imf::NO_COMPRESSION, false},
      {"rgb-zip.exr", false, Imf::HALF, Imf::ZIP_COMPRESSION, false},
      {"rgb-piz.exr", false, Imf::HALF, Imf::PIZ_COMPRESSION, false},
      {"rgb-rle.exr", false, Imf::FLOAT, Imf::RLE_COMPRESSION, false},
      {"rgb-tiled.exr", false, Imf::HALF, Imf::ZIPS_COMPRESSION, true},
      {"rgb-offset.exr", false, Imf::FLOAT, Imf::NO_COMPRESSION, false, -2, 3},
  };
  for (const ExrSeed &seed : exrSeeds)
    for (const fs::path &folder : {texture, image})
      writeExrFile(at(folder, seed.name), seed.grey, seed.type, seed.compression, seed.tiled, seed.originX,
                   seed.originY);

  radiant::Image rendered(kWidth, kHeight);
  for (size_t i = 0; i < rendered.rgb.size(); ++i) rendered.rgb[i] = float(i);
  rendered.emitterFraction.assign(size_t(kWidth) * kHeight, 0.5f);
  rendered.quantity = "radiance";
  radiant::writeExr(rendered, at(image, "rendered.exr"));
  rendered.wavelengths = {450, 550, 650};
  rendered.spectral.assign(rendered.rgb.begin(), rendered.rgb.end());
  radiant::writeExr(rendered, at(image, "spectral.exr"));
  writePfmFile(at(image, "colour-little.pfm"), true, false);
  writePfmFile(at(image, "colour-big.pfm"), true, true);
  writePfmFile(at(image, "grey-little.pfm"), false, false);
  return 0;
}
