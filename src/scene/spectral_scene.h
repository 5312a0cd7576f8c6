// Spectral scenes: materials given as spectra, run three wavelengths at a time
// through the RGB machinery (docs/spectral.md; Cohen & Wallace §9.5).
//
// A spectral scene keeps every spectrum in Material::spectra and its sample
// wavelengths in Scene::spectral. A pass sets each material's three bands to
// its spectra at three of those wavelengths; the solution and the renderers of
// that pass then compute radiance at exactly those wavelengths, unchanged.
// Outside a pass the bands hold the spectra's linear sRGB colour, so code that
// knows nothing of spectra (a preview, a report) still sees a sensible scene.
#pragma once

#include "colour/spectrum.h"
#include "scene/scene.h"

namespace radiant {

/// Sets every material's bands to its spectra at the wavelengths of `pass`
/// (SpectralSettings::wavelength). Grey values are left as they are.
void applySpectralPass(Scene &scene, int pass);

/// Sets every material's bands to its spectra's linear sRGB colour (CIE 1931
/// over the scene's wavelength range, then `balance`), clamped to what the
/// stages accept: reflectance into [0, 0.999], specular into [0, 1], emission ≥ 0.
void applySpectralColour(Scene &scene, WhiteBalance balance = WhiteBalance::None);

/// Makes a spectral scene an RGB one (render/solve --colour rgb): its colours
/// as applySpectralColour gives them, the spectra dropped. One pass instead of
/// ⌈N/3⌉; the colour of interreflections is approximated (a product of sRGB
/// colours is not the colour of the product of spectra).
void convertToRgbScene(Scene &scene, WhiteBalance balance = WhiteBalance::None);

/// The colour matching of a spectral scene's wavelengths.
BandColourMatching bandColourMatching(const Scene &scene);

/// "400–440 nm": the wavelengths of a pass, for progress and messages.
std::string passWavelengthLabel(const Scene &scene, int pass);

/// True when some material emits at one of the pass's wavelengths.
bool passHasEmission(const Scene &scene, int pass);

}  // namespace radiant
