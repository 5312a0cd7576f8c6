// From the films of a spectral scene's passes to one colour image (docs/spectral.md).
//
// Pass p rendered the scene at wavelengths 3p, 3p+1, 3p+2 in its three bands
// (scene/spectral_scene.h). Colour is formed only here, at display: the band
// values are taken as a piecewise-linear spectrum and integrated against the
// CIE 1931 colour-matching functions (colour/spectrum.h, BandColourMatching),
// giving XYZ and then linear sRGB in the same radiance units as an RGB render.
#pragma once

#include <functional>
#include <vector>

#include "colour/spectrum.h"
#include "io/image.h"
#include "render/film.h"
#include "scene/scene.h"

namespace radiant {

struct SpectralImages {
  Image colour;    ///< linear sRGB radiance, W·sr⁻¹·m⁻², with the per-wavelength channels attached
  Image variance;  ///< an upper bound of the variance of each colour channel's mean
};

/// Combines one film per pass (films[p] for pass p, all the same size).
/// The variance of a weighted sum of correlated band estimates (the passes
/// share seeds) is bounded by (Σ|w_i|σ_i)² (Cauchy–Schwarz), which is what
/// `variance` holds: conservative, never optimistic.
SpectralImages combineSpectralFilms(const std::vector<Film> &films, const SpectralSettings &spectral,
                                    WhiteBalance balance);

/// Renders every pass of a scene and forms its image: one pass for an RGB
/// scene (the film's mean and variance, nothing else), ⌈N/3⌉ for a spectral one
/// (applySpectralPass, then combineSpectralFilms; afterwards the materials hold
/// their colours again, applySpectralColour). `renderPass(pass, film)` fills a
/// film of the image's size at the scene's current bands; a spectral pass
/// with no emission at its wavelengths is left black without calling it.
SpectralImages renderPasses(Scene &scene, int width, int height, WhiteBalance balance,
                            const std::function<void(int pass, Film &film)> &renderPass);

}  // namespace radiant
