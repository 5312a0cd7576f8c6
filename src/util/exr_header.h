// OpenEXR files checked before OpenEXR reads them (used by io/image.cpp's
// readImage and texture/texture_file.cpp's Texture::load).
#pragma once

#include <ImfIO.h>

#include <cstdint>
#include <string>

namespace radiant {

/// The data window of an OpenEXR file, inclusive (OpenEXR's Box2i).
struct ExrDataWindow {
  int minX = 0, minY = 0, maxX = 0, maxY = 0;
  long long width() const { return static_cast<long long>(maxX) - minX + 1; }
  long long height() const { return static_cast<long long>(maxY) - minY + 1; }
};

/// Reads the OpenEXR file at `path` whole into `bytes` (util/input_file.h:
/// regular files only), walks its headers before OpenEXR reads them, and returns the
/// first part's data window, so that a reader can refuse a size before
/// OpenEXR allocates for it. OpenEXR 3.1 allocates whatever an attribute says
/// it holds (up to 2 GB) before reading it, and a line-offset table for the
/// whole data window: a 100-byte file could claim gigabytes. Throws
/// InputError naming the file for an attribute larger than what is left of
/// the file, a header that does not end, or no box2i dataWindow.
ExrDataWindow checkExrHeaders(const std::string &path, std::string &bytes);

/// OpenEXR's input over the bytes checkExrHeaders read, so that OpenEXR reads
/// what was checked and never opens the file again by name.
class ExrMemoryStream : public Imf::IStream {
 public:
  ExrMemoryStream(const std::string &bytes, const std::string &path);
  bool read(char c[], int n) override;
  uint64_t tellg() override { return position_; }
  void seekg(uint64_t position) override { position_ = position; }  // past the end: the next read throws

 private:
  const std::string &bytes_;
  uint64_t position_ = 0;
};

}  // namespace radiant
