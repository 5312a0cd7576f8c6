#include "io/image.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <fmt/format.h>
#include <png.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>

#include "util/atomic_file.h"
#include "util/error.h"
#include "util/exr_header.h"
#include "util/file_extension.h"
#include "util/input_file.h"

namespace radiant {

namespace {

/// render's per-pixel emitter coverage, and what the pixels hold (image.h).
constexpr const char *kEmitterChannel = "emitter";
constexpr const char *kQuantityAttribute = "radiantQuantity";
constexpr const char *kSamplesAttribute = "radiantSamplesPerPixel";
constexpr const char *kInterruptedAttribute = "radiantInterrupted";

}  // namespace

double srgbEncode(double linear) {
  if (!(linear > 0)) return 0;
  if (linear >= 1) return 1;
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
}

bool isSupportedImageExtension(const std::string &path) {
  std::string ext = lowercaseExtension(path);
  return ext == ".exr" || ext == ".pfm" || ext == ".hdr" || ext == ".png";
}

bool isLinearImageExtension(const std::string &path) {
  std::string ext = lowercaseExtension(path);
  return ext == ".exr" || ext == ".pfm" || ext == ".hdr";
}

void writeImage(const Image &image, const std::string &path, double exposureStops) {
  std::string ext = lowercaseExtension(path);
  if (ext == ".exr") return writeExr(image, path);
  if (ext == ".pfm") return writePfm(image, path);
  if (ext == ".hdr") return writeHdr(image, path);
  if (ext == ".png") return writePng(image, path, exposureStops);
  throw std::runtime_error("cannot write '" + path + "': unknown image extension (expected .exr, .pfm, .hdr or .png)");
}

namespace {
/// Fichet et al. 2021: emissive Stokes component 0 at a wavelength, the
/// decimal point written as a comma ('.' separates layers): "S0.412,5nm".
std::string spectralChannelName(double nm) {
  std::string number = fmt::format("{:g}", nm);
  std::replace(number.begin(), number.end(), '.', ',');
  return "S0." + number + "nm";
}
}  // namespace

void writeExr(const Image &image, const std::string &path) {
  writeAtomically(path, [&](const std::string &temporary) {
    Imf::Header header(image.width, image.height);
    header.channels().insert("R", Imf::Channel(Imf::FLOAT));
    header.channels().insert("G", Imf::Channel(Imf::FLOAT));
    header.channels().insert("B", Imf::Channel(Imf::FLOAT));
    const bool hasEmitter = image.emitterFraction.size() == size_t(image.width) * image.height;
    if (hasEmitter) header.channels().insert(kEmitterChannel, Imf::Channel(Imf::FLOAT));
    if (!image.quantity.empty()) header.insert(kQuantityAttribute, Imf::StringAttribute(image.quantity));
    if (image.samplesPerPixel > 0) header.insert(kSamplesAttribute, Imf::IntAttribute(image.samplesPerPixel));
    if (image.interrupted) header.insert(kInterruptedAttribute, Imf::IntAttribute(1));
    const size_t bands = image.wavelengths.size();
    const bool hasSpectra = bands > 0 && image.spectral.size() == bands * image.width * image.height;
    std::vector<std::string> spectralNames;
    if (hasSpectra) {
      for (double nm : image.wavelengths) {
        spectralNames.push_back(spectralChannelName(nm));
        header.channels().insert(spectralNames.back(), Imf::Channel(Imf::FLOAT));
      }
      header.insert("spectralLayoutVersion", Imf::StringAttribute("1.0"));
      header.insert("emissiveUnits",
                    Imf::StringAttribute(image.quantity == "irradiance" ? "W.m^-2.nm^-1" : "W.m^-2.sr^-1.nm^-1"));
    }
    Imf::OutputFile file(temporary.c_str(), header);
    Imf::FrameBuffer frame;
    const size_t xStride = 3 * sizeof(float), yStride = xStride * image.width;
    char *base = reinterpret_cast<char *>(const_cast<float *>(image.rgb.data()));
    frame.insert("R", Imf::Slice(Imf::FLOAT, base, xStride, yStride));
    frame.insert("G", Imf::Slice(Imf::FLOAT, base + sizeof(float), xStride, yStride));
    frame.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xStride, yStride));
    if (hasEmitter)
      frame.insert(kEmitterChannel,
                   Imf::Slice(Imf::FLOAT, reinterpret_cast<char *>(const_cast<float *>(image.emitterFraction.data())),
                              sizeof(float), sizeof(float) * image.width));
    for (size_t i = 0; hasSpectra && i < bands; ++i)
      frame.insert(spectralNames[i],
                   Imf::Slice(Imf::FLOAT, reinterpret_cast<char *>(const_cast<float *>(image.spectral.data() + i)),
                              bands * sizeof(float), bands * sizeof(float) * image.width));
    file.setFrameBuffer(frame);
    file.writePixels(image.height);
  });
}

void writePfm(const Image &image, const std::string &path) {
  writeAtomically(path, [&](const std::string &temporary) {
    std::ofstream out(temporary, std::ios::binary);
    if (!out) throw std::runtime_error("cannot open for writing");
    // Negative scale: little-endian floats. PFM stores rows bottom to top.
    out << "PF\n" << image.width << " " << image.height << "\n-1.0\n";
    for (int y = image.height - 1; y >= 0; --y)
      out.write(reinterpret_cast<const char *>(image.pixel(0, y)), std::streamsize(sizeof(float)) * 3 * image.width);
    if (!out) throw std::runtime_error("write failed");
  });
}

void writeHdr(const Image &image, const std::string &path) {
  // RGBE holds no sign and no NaN: those pixels are written as 0.
  std::vector<float> rgb(image.rgb.size());
  for (size_t k = 0; k < rgb.size(); ++k)
    rgb[k] = std::isfinite(image.rgb[k]) && image.rgb[k] > 0 ? image.rgb[k] : 0.0f;
  writeAtomically(path, [&](const std::string &temporary) {
    // stb writes "#?RADIANCE", FORMAT=32-bit_rle_rgbe, EXPOSURE=1 and new-style RLE scanlines, top row first.
    if (!stbi_write_hdr(temporary.c_str(), image.width, image.height, 3, rgb.data()))
      throw std::runtime_error("Radiance HDR encoder failed");
  });
}

void writePngBytes(const std::vector<unsigned char> &rgb, int width, int height, const std::string &path) {
  writeAtomically(path, [&](const std::string &temporary) {
    if (!stbi_write_png(temporary.c_str(), width, height, 3, rgb.data(), width * 3))
      throw std::runtime_error("PNG encoder failed");
  });
}

std::vector<unsigned char> encodePng(const std::vector<unsigned char> &pixels, int width, int height, int channels) {
  std::vector<unsigned char> png;
  auto append = [](void *context, void *data, int size) {
    auto *out = static_cast<std::vector<unsigned char> *>(context);
    const auto *bytes = static_cast<const unsigned char *>(data);
    out->insert(out->end(), bytes, bytes + size);
  };
  if (!stbi_write_png_to_func(append, &png, width, height, channels, pixels.data(), width * channels))
    throw std::runtime_error("PNG encoder failed");
  return png;
}

void writePng16(const std::vector<uint16_t> &rgb, int width, int height, const std::string &path) {
  writeAtomically(path, [&](const std::string &temporary) {
    std::FILE *out = std::fopen(temporary.c_str(), "wb");
    if (!out) throw std::runtime_error("cannot open for writing");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    // libpng reports errors by longjmp; the rows are built before it, so nothing here needs unwinding.
    std::vector<unsigned char> row(size_t(width) * 6);
    bool ok = png && info;
    if (ok && setjmp(png_jmpbuf(png)) == 0) {
      png_init_io(png, out);
      png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 16, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                   PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
      png_write_info(png, info);
      for (int y = 0; y < height; ++y) {
        for (size_t i = 0; i < size_t(width) * 3; ++i) {  // PNG stores 16-bit samples big-endian
          uint16_t v = rgb[size_t(y) * width * 3 + i];
          row[2 * i] = static_cast<unsigned char>(v >> 8);
          row[2 * i + 1] = static_cast<unsigned char>(v & 0xFF);
        }
        png_write_row(png, row.data());
      }
      png_write_end(png, nullptr);
    } else {
      ok = false;
    }
    png_destroy_write_struct(&png, &info);
    bool closed = std::fclose(out) == 0;
    if (!ok || !closed) throw std::runtime_error("PNG encoder failed");
  });
}

void writePng(const Image &image, const std::string &path, double exposureStops) {
  const double scale = std::exp2(exposureStops);
  std::vector<unsigned char> bytes(image.rgb.size());
  for (size_t i = 0; i < image.rgb.size(); ++i)
    bytes[i] = static_cast<unsigned char>(std::lround(255.0 * srgbEncode(image.rgb[i] * scale)));
  writePngBytes(bytes, image.width, image.height, path);
}

static Image readPfm(const std::string &path) {
  InputLocation where{path};
  std::istringstream in(readInputFile(path, where, "PFM image"));
  std::string magic;
  long long width = 0, height = 0;
  double scale = 0;
  in >> magic >> width >> height >> scale;
  if (!in || (magic != "PF" && magic != "Pf"))
    throw InputError(where, "not a PFM file (expected a 'PF' or 'Pf' header with width, height and scale)");
  if (width < 1 || height < 1 || width > 65536 || height > 65536 || width * height > (1LL << 28))
    throw InputError(where, "PFM size " + std::to_string(width) + "x" + std::to_string(height) + " is out of range");
  in.get();
  int channels = magic == "PF" ? 3 : 1;
  // PFM is uncompressed: a file shorter than its header says is refused
  // before the pixels are allocated (a 20-byte header could claim 3 GB).
  const std::streamoff pixelsStart = in.tellg();
  in.seekg(0, std::ios::end);
  const std::streamoff fileSize = in.tellg();
  in.seekg(pixelsStart);
  const long long pixelBytes = width * height * channels * static_cast<long long>(sizeof(float));
  if (!in || fileSize - pixelsStart < pixelBytes)
    throw InputError(where,
                     fmt::format("truncated: the header says {}x{} {}, {} bytes of pixels, and the file holds {} "
                                 "after its header",
                                 width, height, channels == 3 ? "colour" : "grey", pixelBytes,
                                 in ? static_cast<long long>(fileSize - pixelsStart) : 0LL));
  std::vector<float> raw(size_t(width) * height * channels);
  in.read(reinterpret_cast<char *>(raw.data()), std::streamsize(raw.size() * sizeof(float)));
  if (!in) throw InputError(where, "truncated PFM pixel data");
  if (scale > 0) {  // big-endian data
    for (float &f : raw) {
      auto *b = reinterpret_cast<unsigned char *>(&f);
      std::swap(b[0], b[3]);
      std::swap(b[1], b[2]);
    }
  }
  Image image(static_cast<int>(width), static_cast<int>(height));
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c)
        image.pixel(x, image.height - 1 - y)[c] = raw[(size_t(y) * width + x) * channels + (channels == 3 ? c : 0)];
  return image;
}

static Image readExr(const std::string &path) {
  InputLocation where{path};
  // Before OpenEXR allocates for what the headers claim (checkExrHeaders).
  std::string bytes;
  const ExrDataWindow claimed = checkExrHeaders(path, bytes);
  // Divided, not multiplied: each side may be up to 2^32, and the product overflow.
  if (claimed.width() > (1LL << 28) / claimed.height()) throw InputError(where, "EXR data window is too large");
  try {
    ExrMemoryStream stream(bytes, path);
    Imf::InputFile file(stream);
    Imath::Box2i window = file.header().dataWindow();
    long long width = static_cast<long long>(window.max.x) - window.min.x + 1;
    long long height = static_cast<long long>(window.max.y) - window.min.y + 1;
    if (width < 1 || height < 1 || width * height > (1LL << 28))
      throw InputError(where, "EXR data window is empty or too large");
    // A row is the least OpenEXR reads at once: wider than 2^20 pixels (no
    // panorama is), one row of a file that holds nothing would cost 12 MB and more.
    if (width > (1LL << 20))
      throw InputError(where, fmt::format("EXR data window is {} pixels wide; at most 1048576 are read", width));
    Image image;
    image.width = static_cast<int>(width), image.height = static_cast<int>(height);
    const Imf::ChannelList &channels = file.header().channels();
    bool hasRgb = channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B");
    bool hasY = channels.findChannel("Y");
    if (!hasRgb && !hasY) throw InputError(where, "EXR file has neither R, G, B nor Y channels");
    const bool hasEmitter = channels.findChannel(kEmitterChannel) != nullptr;
    if (const auto *quantity = file.header().findTypedAttribute<Imf::StringAttribute>(kQuantityAttribute))
      image.quantity = quantity->value();
    if (const auto *samples = file.header().findTypedAttribute<Imf::IntAttribute>(kSamplesAttribute))
      image.samplesPerPixel = samples->value();
    if (const auto *interrupted = file.header().findTypedAttribute<Imf::IntAttribute>(kInterruptedAttribute))
      image.interrupted = interrupted->value() != 0;
    // Read in strips of about 2^20 pixels, the image growing only by what was
    // decoded: a file whose header claims 2^28 pixels but holds a few bytes
    // fails at its first strip, having allocated 12 MB, not 3 GB (issue 17's
    // fuzzing: no huge allocation for bad input).
    const int stripRows = static_cast<int>(std::clamp<long long>((1LL << 20) / width, 1, height));
    std::vector<float> strip(size_t(stripRows) * width * 3), stripEmitter(hasEmitter ? size_t(stripRows) * width : 0);
    const size_t xStride = 3 * sizeof(float), yStride = xStride * size_t(width);
    const char *names[3] = {"R", "G", "B"};
    for (long long y0 = window.min.y; y0 <= window.max.y; y0 += stripRows) {
      const int y1 = static_cast<int>(std::min<long long>(window.max.y, y0 + stripRows - 1));
      // OpenEXR addresses the buffer by absolute pixel position; Slice::Make
      // shifts the pointer by the strip's origin (a negative origin wrapped
      // the size_t arithmetic this once did by hand: undefined pointer overflow).
      const Imath::Box2i rows(Imath::V2i(window.min.x, static_cast<int>(y0)), Imath::V2i(window.max.x, y1));
      Imf::FrameBuffer frame;
      for (int c = 0; c < (hasRgb ? 3 : 1); ++c)
        frame.insert(hasRgb ? names[c] : "Y", Imf::Slice::Make(Imf::FLOAT, strip.data() + c, rows, xStride, yStride));
      if (hasEmitter)
        frame.insert(kEmitterChannel,
                     Imf::Slice::Make(Imf::FLOAT, stripEmitter.data(), rows, sizeof(float), sizeof(float) * width));
      file.setFrameBuffer(frame);
      file.readPixels(static_cast<int>(y0), y1);
      const size_t pixels = size_t(y1 - y0 + 1) * width;
      if (!hasRgb)  // grey image: luminance into all three channels
        for (size_t i = 0; i < 3 * pixels; i += 3) strip[i + 1] = strip[i + 2] = strip[i];
      image.rgb.insert(image.rgb.end(), strip.begin(), strip.begin() + 3 * pixels);
      if (hasEmitter)
        image.emitterFraction.insert(image.emitterFraction.end(), stripEmitter.begin(), stripEmitter.begin() + pixels);
    }
    return image;
  } catch (const InputError &) {
    throw;
  } catch (const std::exception &e) {
    throw InputError(where, std::string("cannot read OpenEXR image: ") + e.what());
  }
}

namespace {
/// Radiance RGBE (.hdr) through stb_image: the values as stored, EXPOSURE not applied (Radiant writes 1).
Image readHdr(const std::string &path) {
  const std::string bytes = readInputFile(path, InputLocation{path}, "Radiance HDR image");
  const auto *data = reinterpret_cast<const stbi_uc *>(bytes.data());
  // stb_image takes an int length: a file of 2 GiB and more is refused as not an HDR image.
  const int length = bytes.size() < size_t(INT32_MAX) ? int(bytes.size()) : 0;
  const bool isHdr = length > 0 && stbi_is_hdr_from_memory(data, length) != 0;
  if (!isHdr) throw InputError(InputLocation{path}, "not a Radiance HDR (RGBE) image: no '#?RADIANCE' header");
  // stb_image allocates what the resolution line claims and fills a truncated
  // file's missing scanlines without an error: a 105-byte file claiming
  // 3 × 7777772 pixels took 9 s and 585 MB (fuzzed, issue 38). A scanline
  // holds at least 4 bytes a pixel, or, run-length encoded (widths 8 to
  // 32767), its 4-byte marker and a 2-byte run per 127 pixels of each channel.
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(data, length, &width, &height, &channels))
    throw InputError(InputLocation{path}, std::string("cannot read Radiance HDR image: ") + stbi_failure_reason());
  const long long scanlineBytes = width >= 8 && width < 32768 ? 4 + 8 * ((width + 126LL) / 127) : 4LL * width;
  if (double(width) * height > double(1LL << 28) || scanlineBytes * height > length)
    throw InputError(InputLocation{path},
                     fmt::format("truncated: the header says {}x{} pixels, at least {} bytes of scanlines, and the "
                                 "file has {} bytes in all",
                                 width, height, scanlineBytes * height, length));
  float *pixels = stbi_loadf_from_memory(data, length, &width, &height, &channels, 3);
  if (!pixels)
    throw InputError(InputLocation{path}, std::string("cannot read Radiance HDR image: ") + stbi_failure_reason());
  Image image(width, height);
  std::copy(pixels, pixels + size_t(width) * size_t(height) * 3, image.rgb.begin());
  stbi_image_free(pixels);
  return image;
}
}  // namespace

Image readImage(const std::string &path) {
  if (checkInputFile(path).status == InputFileRead::Status::Missing)
    throw InputError(InputLocation{path}, "no such file");
  std::string ext = lowercaseExtension(path);
  if (ext == ".exr") return readExr(path);
  if (ext == ".pfm") return readPfm(path);
  if (ext == ".hdr") return readHdr(path);
  throw InputError(InputLocation{path}, "unsupported image format (expected .exr, .pfm or .hdr, linear radiance)");
}

}  // namespace radiant
