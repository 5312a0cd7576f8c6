#include "export/ply_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <fstream>

#include "util/atomic_file.h"

namespace radiant {

static_assert(std::endian::native == std::endian::little, "the PLY writer writes the machine's own byte order");

namespace {

template <typename T>
void put(std::string &out, T value) {
  out.append(reinterpret_cast<const char *>(&value), sizeof(T));
}

}  // namespace

void writePly(const BakedMesh &baked, const DisplayLinearFunction &display, const std::string &path) {
  size_t vertices = 0, triangles = 0;
  for (const BakedPrimitive &p : baked.primitives) vertices += p.vertexCount(), triangles += p.triangleCount();
  std::string out = fmt::format(
      "ply\n"
      "format binary_little_endian 1.0\n"
      "comment Radiant {} radiosity solution: {} elements; metres; vertex colours are display values (sRGB)\n"
      "comment radiance_*: outgoing radiance L = B/pi, W/(sr m^2); irradiance_*: arriving H, W/m^2 (linear Rec.709)\n"
      "element vertex {}\n"
      "property float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      "property float radiance_r\nproperty float radiance_g\nproperty float radiance_b\n"
      "property float irradiance_r\nproperty float irradiance_g\nproperty float irradiance_b\n"
      "element face {}\n"
      "property list uchar uint vertex_indices\n"
      "end_header\n",
      RADIANT_VERSION, baked.elements, vertices, triangles);
  out.reserve(out.size() + vertices * 39 + triangles * 13);
  for (const BakedPrimitive &p : baked.primitives)
    for (size_t v = 0; v < p.vertexCount(); ++v) {
      for (int c = 0; c < 3; ++c) put(out, p.positions[3 * v + c]);
      for (int c = 0; c < 3; ++c) put(out, p.normals[3 * v + c]);
      double encoded[3] = {0, 0, 0};
      if (display) display(&p.radiance[3 * v], encoded);
      for (int c = 0; c < 3; ++c) put(out, uint8_t(std::lround(255 * std::clamp(encoded[c], 0.0, 1.0))));
      for (int c = 0; c < 3; ++c) put(out, p.radiance[3 * v + c]);
      for (int c = 0; c < 3; ++c) put(out, p.irradiance[3 * v + c]);
    }
  uint32_t offset = 0;
  for (const BakedPrimitive &p : baked.primitives) {
    for (size_t t = 0; t < p.triangleCount(); ++t) {
      put(out, uint8_t(3));
      for (int k = 0; k < 3; ++k) put(out, p.indices[3 * t + k] + offset);
    }
    offset += uint32_t(p.vertexCount());
  }
  writeAtomically(path, [&](const std::string &temporary) {
    std::ofstream file(temporary, std::ios::binary);
    file.write(out.data(), std::streamsize(out.size()));
    file.close();
    if (!file) throw std::runtime_error("write failed (disk full?)");
  });
}

}  // namespace radiant
