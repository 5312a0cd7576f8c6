// Images on disk: linear HDR (OpenEXR float, PFM, Radiance RGBE) and display PNG.
//
// Every writer goes through a temporary file in the target's folder and a
// rename, so a failed or interrupted write never leaves a partial file over a
// good one.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "util/spectrum.h"

namespace radiant {

/// Linear RGB float image, row-major from the top-left pixel.
struct Image {
  int width = 0, height = 0;
  std::vector<float> rgb;  ///< 3 floats per pixel
  /// Optional, one float per pixel: the fraction of the pixel's camera rays
  /// whose first hit is the front of an emitter (render/emitter_coverage.h).
  /// Empty when unknown. OpenEXR keeps it as the channel "emitter"; PFM drops it.
  std::vector<float> emitterFraction;
  /// What the pixels hold, when known: "radiance" (W·sr⁻¹·m⁻², what render
  /// writes) or "irradiance" (W·m⁻²). OpenEXR keeps it as the string attribute
  /// "radiantQuantity"; empty when unknown.
  std::string quantity;
  /// Samples per pixel that every pixel has (0: unknown); OpenEXR keeps it as
  /// the int attribute "radiantSamplesPerPixel".
  int samplesPerPixel = 0;
  /// The render was stopped by Ctrl-C before its samples or time budget were
  /// reached (some pixels may hold one round more than samplesPerPixel);
  /// OpenEXR's int attribute "radiantInterrupted" = 1.
  bool interrupted = false;
  /// Spectral renders only: the sample wavelengths (nm) and, per pixel, one
  /// float per wavelength of spectral radiance in W·m⁻²·sr⁻¹·nm⁻¹. OpenEXR
  /// keeps them as channels "S0.<λ>nm" (Fichet, Pacanowski & Wilkie 2021,
  /// "An OpenEXR layout for spectral images", JCGT 10(3)); PFM and PNG drop them.
  std::vector<double> wavelengths;
  std::vector<float> spectral;

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(size_t(w) * h * 3, 0.0f) {}
  float *pixel(int x, int y) { return &rgb[(size_t(y) * width + x) * 3]; }
  const float *pixel(int x, int y) const { return &rgb[(size_t(y) * width + x) * 3]; }
};

/// Writes by extension: .exr (32-bit float), .pfm, .hdr (Radiance RGBE), .png (sRGB after
/// 2^exposureStops scaling). Throws std::runtime_error naming the file.
void writeImage(const Image &image, const std::string &path, double exposureStops = 0);
void writeExr(const Image &image, const std::string &path);
void writePfm(const Image &image, const std::string &path);
/// Radiance RGBE (Ward, Graphics Gems II): "#?RADIANCE", FORMAT=32-bit_rle_rgbe,
/// EXPOSURE=1, run-length-encoded scanlines; about 1 % precision (8-bit mantissas
/// sharing an exponent). The values are Radiant's as they are (W·sr⁻¹·m⁻²);
/// Radiance's tools take luminance as 179 lm/W × Y, not 683 (docs/tone-mapping.md).
/// Negative and non-finite values become 0; emitter coverage and spectra are dropped.
void writeHdr(const Image &image, const std::string &path);
/// 8-bit sRGB (IEC 61966-2-1 curve), radiance scaled by 2^exposureStops and clipped to [0,1].
void writePng(const Image &image, const std::string &path, double exposureStops = 0);
/// 8-bit PNG from already display-encoded RGB bytes.
void writePngBytes(const std::vector<unsigned char> &rgb, int width, int height, const std::string &path);
/// An 8-bit PNG in memory, `channels` (1–4) bytes per pixel, rows top first.
/// Throws std::runtime_error if the encoder fails.
std::vector<unsigned char> encodePng(const std::vector<unsigned char> &pixels, int width, int height, int channels);
/// 16-bit PNG (libpng) from display-encoded RGB values 0…65535, like the 8-bit
/// writer without colour-space chunks (viewers take untagged PNG as sRGB).
void writePng16(const std::vector<uint16_t> &rgb, int width, int height, const std::string &path);

/// Reads .exr, .pfm or .hdr (linear), with the EXR's "emitter" channel and
/// "radiantQuantity" attribute when present. Throws InputError naming the file.
Image readImage(const std::string &path);

/// The sRGB transfer function (linear [0,1] → encoded [0,1]).
double srgbEncode(double linear);

/// True if the extension is one writeImage knows.
bool isSupportedImageExtension(const std::string &path);
/// True for the formats that keep linear values as they are (.exr, .pfm, .hdr), not display-mapped (.png).
bool isLinearImageExtension(const std::string &path);

}  // namespace radiant
