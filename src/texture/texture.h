// Image textures for surface detail (Cohen & Wallace §9.4, eq. 9.11;
// Chen & Wu, SIGGRAPH 1990):
// loading, filtered lookups, footprint averages for the radiosity solver, and
// height-field gradients for bump maps.
//
// Texture space: u to the right, v up, (0, 0) at the image's bottom-left
// corner and (1, 1) at its top-right (the OBJ/MTL convention); texel (i, j)
// covers [i/w, (i+1)/w] × [1 − (j+1)/h, 1 − j/h] with row j = 0 at the top
// of the file, and its value sits at the texel's centre.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "util/error.h"
#include "util/spectrum.h"

namespace radiant {

enum class TextureWrap {
  Repeat,  ///< the image tiles the plane (u and v modulo 1)
  Clamp,   ///< coordinates outside [0, 1] take the nearest edge texel
};

/// How a file's stored values become texture values.
enum class TextureEncoding {
  Colour,  ///< reflectance: 8- and 16-bit files are sRGB-decoded (IEC 61966-2-1) to linear; EXR is linear already
  Data,    ///< heights or normals: values as stored, 8/16-bit scaled to [0, 1]; never sRGB-decoded
};

/// A texture in texture space (u, v) → linear value per band, with its mip-map pyramid.
class Texture {
 public:
  /// The largest texture accepted, in texels of the finest level (4096 × 4096):
  /// a bigger file is refused before its pixels are allocated.
  static constexpr long long kMaxTexels = 1LL << 24;

  /// Loads PNG or JPEG (stb_image: 8 or 16 bits per channel; grey, grey + alpha,
  /// RGB or RGBA, alpha ignored, grey copied to every band) or OpenEXR (R, G, B
  /// or Y channels, linear). Throws InputError naming the file for a missing,
  /// unreadable, corrupt, empty or too large file.
  static Texture load(const std::string &path, TextureEncoding encoding, TextureWrap wrap = TextureWrap::Repeat);
  /// A PNG or JPEG image held in memory (one embedded in a glTF file), decoded
  /// as load() decodes a file; errors are InputErrors at `source` (the file
  /// and JSON path of the image).
  static Texture decode(std::span<const unsigned char> bytes, const InputLocation &source, TextureEncoding encoding,
                        TextureWrap wrap = TextureWrap::Repeat);

  /// A texture from linear texels, `width` × `height`, row 0 at the top (v = 1).
  Texture(int width, int height, std::vector<Bands> texels, TextureWrap wrap = TextureWrap::Repeat);

  int width() const;
  int height() const;
  TextureWrap wrap() const { return wrap_; }
  /// Mean of all texels of the finest level.
  Bands mean() const;
  /// The finest level's texels, 3 floats each, row 0 at the top (for fingerprints).
  std::span<const float> finestTexels() const { return levels_.front().texels; }

  /// Bilinear interpolation of the finest level at (u, v).
  Bands bilinear(double u, double v) const;
  /// Trilinear mip-mapped lookup for a pixel whose footprint is `footprint`
  /// wide in texture space (e.g. the larger side of the pixel's uv
  /// footprint): the level whose texels are that wide, blended with the next.
  /// A footprint of 0 or below one texel is bilinear().
  Bands filtered(double u, double v, double footprint) const;
  /// The mean of the texture over a convex polygon in texture space (an
  /// element's footprint), integrated over the texels it covers — not
  /// point-sampled at its centre — honouring the wrap mode. A polygon of zero
  /// area gives bilinear() at its first vertex.
  Bands average(std::span<const std::array<double, 2>> polygon) const;
  /// Gradient (∂h/∂u, ∂h/∂v) of the height h = mean of the bands, of the
  /// bilinear reconstruction of the finest level (per unit of u and v), for bump maps.
  std::array<double, 2> gradient(double u, double v) const;

 private:
  struct Level {
    int width = 0, height = 0;
    std::vector<float> texels;  ///< 3 floats per texel, row 0 at the top
  };
  /// From the finest level as stored: load() decodes straight into floats,
  /// avoiding a double-precision copy of a texture of up to kMaxTexels.
  Texture(Level finest, TextureWrap wrap);
  Bands texel(const Level &level, long long i, long long j) const;  ///< with wrap applied
  Bands bilinear(const Level &level, double u, double v) const;

  std::vector<Level> levels_;  ///< levels_[0] finest; each next one half the size (rounded up), to 1 × 1
  TextureWrap wrap_ = TextureWrap::Repeat;
  Bands mean_;  ///< of the finest level, summed once: the solver asks for it per element
};

}  // namespace radiant
