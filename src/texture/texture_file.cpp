// Texture::load: image files to linear texels (sRGB decoded per IEC 61966-2-1).
//
// PNG and JPEG go through stb_image (8 or 16 bits per channel), OpenEXR
// through OpenEXR. The format is recognised by the file's signature, not its
// name, so a text file called .png is reported as what it is. The size is
// read from the header and checked against Texture::kMaxTexels before any
// pixel is decoded, so a hostile or mistaken 50 000 × 50 000 file costs
// nothing. Colour textures in 8/16-bit files are sRGB-encoded by convention
// (what paint programs and cameras write) and are decoded with the IEC
// 61966-2-1 curve; EXR holds linear values already; Data textures (heights)
// are never decoded.
// clang-format off (the definition must stay right above its header)
#define STB_IMAGE_IMPLEMENTATION  // the one definition in the project
#include <stb/stb_image.h>
// clang-format on

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "texture/texture.h"
#include "util/error.h"
#include "util/exr_header.h"
#include "util/input_file.h"

namespace radiant {

namespace {

enum class FileFormat { Png, Jpeg, Exr, Unknown };

/// stb_image's reason for its last failure on this thread.
std::string stbReason() {
  const char *reason = stbi_failure_reason();
  return std::string("stb_image: ") + (reason ? reason : "unknown error");
}

/// The format from the first bytes (fewer than 8 are fine).
FileFormat sniffFormat(std::span<const unsigned char> head) {
  constexpr std::array<unsigned char, 8> png{0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  const size_t got = head.size();
  if (got >= 8 && std::equal(png.begin(), png.end(), head.begin())) return FileFormat::Png;
  if (got >= 3 && head[0] == 0xFF && head[1] == 0xD8 && head[2] == 0xFF) return FileFormat::Jpeg;
  if (got >= 4 && head[0] == 0x76 && head[1] == 0x2F && head[2] == 0x31 && head[3] == 0x01) return FileFormat::Exr;
  return FileFormat::Unknown;
}

/// Refuses a texture above the limit before its pixels are allocated.
void checkSize(const InputLocation &where, long long width, long long height) {
  if (width < 1 || height < 1)
    throw InputError(where, "image is empty (" + std::to_string(width) + "x" + std::to_string(height) + ")");
  // Divided, not multiplied: an OpenEXR data window may be 2^32 on a side, and the product overflow.
  if (width > Texture::kMaxTexels / height)
    throw InputError(where, "image is " + std::to_string(width) + "x" + std::to_string(height) +
                                " texels, more than the limit of " + std::to_string(Texture::kMaxTexels) +
                                " (4096x4096); scale it down");
}

/// IEC 61966-2-1 decode, V ∈ [0, 1] → linear.
double srgbDecode(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

/// Texture value of every stored code 0 … maxCode: one table per file, so a
/// 16-bit texture costs 65 536 pow() calls instead of one per sample.
std::vector<float> codeTable(int maxCode, TextureEncoding encoding) {
  std::vector<float> table(size_t(maxCode) + 1);
  for (int code = 0; code <= maxCode; ++code) {
    const double v = double(code) / maxCode;
    table[size_t(code)] = float(encoding == TextureEncoding::Colour ? srgbDecode(v) : v);
  }
  return table;
}

struct StbFree {
  void operator()(void *pixels) const { stbi_image_free(pixels); }
};

/// Decodes with stb_image, asking for three channels: stb copies grey to all
/// three and drops alpha, which is what the texture wants.
template <typename Sample>
std::vector<float> decodeStb(const InputLocation &where, std::span<const unsigned char> bytes, int width, int height,
                             TextureEncoding encoding) {
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<Sample, StbFree> pixels;
  const int size = int(bytes.size());  // readStb checked that it fits
  if constexpr (sizeof(Sample) == 2)
    pixels.reset(stbi_load_16_from_memory(bytes.data(), size, &w, &h, &channels, 3));
  else
    pixels.reset(stbi_load_from_memory(bytes.data(), size, &w, &h, &channels, 3));
  if (!pixels) {
    // The header's size and the data's length tell a truncated image from a corrupt one.
    throw InputError(where, "cannot decode the " + std::to_string(width) + "x" + std::to_string(height) +
                                " image from the " + std::string(where.jsonPath.empty() ? "file" : "image") + "'s " +
                                std::to_string(bytes.size()) + " bytes (corrupt or truncated?): " + stbReason());
  }
  if (w != width || h != height) throw InputError(where, "image size changed between header and pixels");
  const std::vector<float> table = codeTable(sizeof(Sample) == 2 ? 65535 : 255, encoding);
  std::vector<float> texels(size_t(width) * height * 3);
  for (size_t k = 0; k < texels.size(); ++k) texels[k] = table[pixels.get()[k]];
  return texels;
}

struct Decoded {
  int width = 0, height = 0;
  std::vector<float> texels;  ///< 3 per texel, row 0 at the top
};

/// Refuses a JPEG with a Huffman table of more than 256 codes. stb_image
/// before 2.28 (Debian 12 ships 2.27) trusts the table's 16 code counts,
/// whose sum can reach 4080, and writes that many code lengths and symbols
/// into arrays of 257 and 256 (stbi__build_huffman, stbi__process_marker):
/// a heap overflow from a 700-byte file. Walks every marker segment, those
/// between progressive scans too, before stb_image sees the file.
void checkJpegHuffmanTables(const InputLocation &where, std::span<const unsigned char> data) {
  auto byte = [&](size_t at) { return at < data.size() ? static_cast<unsigned int>(data[at]) : 0u; };
  size_t at = 2;  // after SOI
  while (at + 4 <= data.size()) {
    if (byte(at) != 0xFF) {  // entropy-coded data: skip to the next marker (not a stuffed FF 00 or an RSTn)
      ++at;
      continue;
    }
    const unsigned marker = byte(at + 1);
    if (marker == 0xFF || marker == 0x00 || (marker >= 0xD0 && marker <= 0xD7) || marker == 0x01) {
      ++at;
      continue;
    }
    if (marker == 0xD9) return;  // EOI
    const size_t length = size_t(byte(at + 2)) << 8 | byte(at + 3);
    if (marker == 0xC4) {
      // DHT: tables of a class/id byte, 16 counts and the symbols, read as
      // stb_image reads them: while the declared length is not used up, even
      // past it (a DHT that claims 3 bytes still has a 17-byte table read),
      // and on from where the last table ends. Past the end of the file stb
      // reads zeros, as byte() does.
      long remaining = long(length) - 2;
      size_t table = at + 4;
      while (remaining > 0) {
        size_t codes = 0;
        for (size_t i = 1; i <= 16; ++i) codes += byte(table + i);
        if (codes > 256)
          throw InputError(where,
                           "corrupt JPEG: a Huffman table declares " + std::to_string(codes) + " codes (at most 256)");
        table += 17 + codes;
        remaining -= long(17 + codes);
      }
      at = table;
      continue;
    }
    at += 2 + length;  // stb_image skips a segment by its length
  }
}

/// PNG or JPEG from memory: the size from the header, checked against the
/// limit, before any pixel is decoded.
Decoded readStb(const InputLocation &where, std::span<const unsigned char> bytes, TextureEncoding encoding) {
  if (bytes.size() > size_t(std::numeric_limits<int>::max()))
    throw InputError(where, "image of " + std::to_string(bytes.size()) + " bytes; stb_image reads at most 2 GiB");
  const int size = int(bytes.size());
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), size, &width, &height, &channels))
    throw InputError(where, "cannot read the image header: " + stbReason());
  checkSize(where, width, height);
  if (stbi_is_16_bit_from_memory(bytes.data(), size))
    return {width, height, decodeStb<stbi_us>(where, bytes, width, height, encoding)};
  return {width, height, decodeStb<stbi_uc>(where, bytes, width, height, encoding)};
}

/// A PNG or JPEG in memory (a file's contents, or an image embedded in a glTF file).
Decoded decodeStbImage(const InputLocation &where, std::span<const unsigned char> bytes, TextureEncoding encoding) {
  switch (sniffFormat(bytes)) {
    case FileFormat::Jpeg:
      checkJpegHuffmanTables(where, bytes);
      return readStb(where, bytes, encoding);
    case FileFormat::Png:
      return readStb(where, bytes, encoding);
    case FileFormat::Exr:
    case FileFormat::Unknown:
      break;
  }
  throw InputError(where,
                   "not an image this program reads: expected PNG or JPEG (the data starts with neither "
                   "signature)");
}

/// OpenEXR, linear already: R, G, B, or Y copied to all three. Like
/// io/image.cpp's reader, but with the texture limit checked on the header's
/// data window (read by checkExrHeaders) before anything is allocated for it.
Decoded readExr(const InputLocation &where) {
  // The size, before OpenEXR allocates for what the headers claim (util/exr_header.h).
  std::string bytes;
  const ExrDataWindow claimed = checkExrHeaders(where.file, bytes);
  checkSize(where, claimed.width(), claimed.height());
  try {
    ExrMemoryStream stream(bytes, where.file);
    Imf::InputFile file(stream);
    const Imath::Box2i window = file.header().dataWindow();
    const long long width = static_cast<long long>(window.max.x) - window.min.x + 1;
    const long long height = static_cast<long long>(window.max.y) - window.min.y + 1;
    checkSize(where, width, height);
    const Imf::ChannelList &channels = file.header().channels();
    const bool rgb = channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B");
    if (!rgb && !channels.findChannel("Y"))
      throw InputError(where, "OpenEXR image has neither R, G, B nor a Y channel");
    Decoded image{int(width), int(height), std::vector<float>(size_t(width) * height * 3)};
    const size_t xStride = 3 * sizeof(float), yStride = xStride * size_t(width);
    // OpenEXR addresses the buffer by absolute pixel position in the data window;
    // Slice::Make shifts the pointer by its origin (by hand, a data window far
    // from (0, 0) moved it below address 0: undefined pointer overflow).
    Imf::FrameBuffer frame;
    const char *names[3] = {"R", "G", "B"};
    for (int c = 0; c < (rgb ? 3 : 1); ++c)
      frame.insert(rgb ? names[c] : "Y",
                   Imf::Slice::Make(Imf::FLOAT, image.texels.data() + c, window, xStride, yStride));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    if (!rgb)
      for (size_t k = 0; k < image.texels.size(); k += 3) image.texels[k + 1] = image.texels[k + 2] = image.texels[k];
    return image;
  } catch (const InputError &) {
    throw;
  } catch (const std::exception &e) {
    throw InputError(where, std::string("cannot read the OpenEXR image: ") + e.what());
  }
}

/// A NaN or infinite reflectance would spread through the whole radiosity
/// solution; refuse it where the user can still see which file is at fault.
void checkFinite(const InputLocation &where, const Decoded &image) {
  for (size_t k = 0; k < image.texels.size(); ++k)
    if (!std::isfinite(image.texels[k])) {
      const size_t texel = k / 3;
      throw InputError(where, "texel (" + std::to_string(texel % size_t(image.width)) + ", " +
                                  std::to_string(texel / size_t(image.width)) + ") is not a finite number");
    }
}

/// The checks and the clamp every decoded texture gets.
void finish(const InputLocation &where, Decoded &image, TextureEncoding encoding) {
  checkFinite(where, image);
  // A colour texture is a reflectance: an EXR's values outside [0, 1] are
  // clamped once here, so that ρ̄ (the mean) and ρ(x) see the same texels.
  if (encoding == TextureEncoding::Colour)
    for (float &v : image.texels) v = std::clamp(v, 0.0f, 1.0f);
}

}  // namespace

Texture Texture::load(const std::string &path, TextureEncoding encoding, TextureWrap wrap) {
  const InputLocation where{path};
  InputFileRead file = tryReadInputFile(path);
  if (file.status == InputFileRead::Status::Missing) throw InputError(where, "no such file");
  if (!file.ok()) throw InputError(where, inputFileProblem(file, "texture '" + path + "'"));
  if (file.bytes.empty()) throw InputError(where, "the file is empty (expected a PNG, JPEG or OpenEXR image)");
  const auto *bytes = reinterpret_cast<const unsigned char *>(file.bytes.data());
  const std::span<const unsigned char> contents(bytes, file.bytes.size());
  Decoded image;
  switch (sniffFormat(contents)) {
    case FileFormat::Jpeg:
    case FileFormat::Png:
      image = decodeStbImage(where, contents, encoding);
      break;
    case FileFormat::Exr:
      image = readExr(where);
      break;
    case FileFormat::Unknown:
      throw InputError(where,
                       "not an image this program reads: expected PNG, JPEG or OpenEXR (the file starts with "
                       "none of their signatures)");
  }
  finish(where, image, encoding);
  return Texture(Level{image.width, image.height, std::move(image.texels)}, wrap);
}

Texture Texture::decode(std::span<const unsigned char> bytes, const InputLocation &source, TextureEncoding encoding,
                        TextureWrap wrap) {
  if (bytes.empty()) throw InputError(source, "the image is empty (expected a PNG or JPEG image)");
  if (sniffFormat(bytes) == FileFormat::Exr)
    throw InputError(source, "an embedded OpenEXR image; embedded images are read as PNG or JPEG");
  Decoded image = decodeStbImage(source, bytes, encoding);
  finish(source, image, encoding);
  return Texture(Level{image.width, image.height, std::move(image.texels)}, wrap);
}

}  // namespace radiant
