// A baked lightmap (export/lightmap_bake.h) as the images a glTF file holds
// (docs/export.md, "Lightmaps"):
//
// - an 8-bit sRGB PNG of the display values T(L) (the tone operator of
//   display/display_mapping.h, as `radiant render` shows the scene), which
//   plain viewers show as the unlit base colour;
// - the irradiance H in Radiance's shared-exponent RGBE (Ward, "Real Pixels",
//   Graphics Gems II, 1991) packed into the four channels of a PNG, for
//   engines that multiply their own albedo by the light: 8 bits of mantissa
//   per channel over a 2^±127 range, where an 8-bit PNG holds 1:255.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "export/baked_mesh.h"
#include "export/lightmap_bake.h"

namespace radiant {

/// Radiance's RGBE: the largest channel's exponent e shared, each channel's
/// mantissa in 8 bits; (0, 0, 0, 0) below 1e-32. Decoding: c' = (c + 0.5)·2^(e − 136).
std::array<uint8_t, 4> encodeRgbe(const float rgb[3]);
std::array<float, 3> decodeRgbe(const std::array<uint8_t, 4> &rgbe);

/// The PNG of the display values plain viewers show: sRGB-encoded T(L).
std::vector<unsigned char> lightmapDisplayPng(const LightmapImages &images, const DisplayLinearFunction &displayLinear);
/// The PNG (RGBA) of the irradiance in RGBE.
std::vector<unsigned char> lightmapIrradiancePng(const LightmapImages &images);

}  // namespace radiant
