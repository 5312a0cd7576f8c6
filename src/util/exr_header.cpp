#include "util/exr_header.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <optional>
#include <stdexcept>

#include "util/error.h"
#include "util/input_file.h"

namespace radiant {

ExrMemoryStream::ExrMemoryStream(const std::string &bytes, const std::string &path)
    : Imf::IStream(path.c_str()), bytes_(bytes) {}

bool ExrMemoryStream::read(char c[], int n) {
  if (n < 0 || position_ > bytes_.size() || uint64_t(n) > bytes_.size() - position_)
    throw std::runtime_error("the file ends before byte " + std::to_string(position_ + uint64_t(std::max(n, 0))));
  std::memcpy(c, bytes_.data() + position_, size_t(n));
  position_ += uint64_t(n);
  return position_ < bytes_.size();
}

ExrDataWindow checkExrHeaders(const std::string &path, std::string &data) {
  const InputLocation where{path};
  auto refuse = [&](const std::string &why) {
    return InputError(where, "cannot read OpenEXR image: " + why);  // the wording of readExr's other refusals
  };
  data = readInputFile(path, where, "OpenEXR image");
  if (data.size() < 8 || data.compare(0, 4, "\x76\x2f\x31\x01") != 0)
    throw refuse("not an OpenEXR file (it does not start with OpenEXR's signature)");
  size_t at = 8;                                   // signature, version and flags
  const bool multipart = uint8_t(data[5]) & 0x10;  // bit 12 of the version field: several headers, then an empty one
  // A null-terminated name or type, at most 255 characters (31 without the long-names flag; OpenEXR checks that).
  auto word = [&](const char *what) {
    const size_t end = data.find('\0', at);
    if (end == std::string::npos || end - at > 255)
      throw refuse(
          fmt::format("the header is truncated or corrupt (an attribute {} at byte {} does not end)", what, at));
    std::string text = data.substr(at, end - at);
    at = end + 1;
    return text;
  };
  std::optional<ExrDataWindow> window;
  for (int part = 0;; ++part) {
    if (part > 0 && (!multipart || (at < data.size() && data[at] == '\0'))) break;
    for (;;) {
      std::string name = word("name");
      if (name.empty()) break;  // the end of this header
      const std::string type = word("type");
      if (data.size() - at < 4) throw refuse("the header is truncated (attribute '" + name + "' has no size)");
      int32_t size;
      std::memcpy(&size, data.data() + at, 4);  // little-endian, as every host radiant runs on
      at += 4;
      if (size < 0 || size_t(size) > data.size() - at)
        throw refuse(fmt::format("the header is corrupt: attribute '{}' claims {} bytes and the file has {} left", name,
                                 size, data.size() - at));
      if (part == 0 && name == "dataWindow" && type == "box2i" && size == 16) {
        int32_t box[4];
        std::memcpy(box, data.data() + at, sizeof box);
        window = ExrDataWindow{box[0], box[1], box[2], box[3]};
      }
      at += size_t(size);
    }
    if (!multipart) break;
  }
  if (!window) throw refuse("the header has no dataWindow (a box2i attribute)");
  if (window->width() < 1 || window->height() < 1)
    throw refuse(fmt::format("the data window is empty ({} x {})", window->width(), window->height()));
  return *window;
}

}  // namespace radiant
