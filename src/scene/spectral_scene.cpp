#include "scene/spectral_scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace radiant {

namespace {

/// The integer range the spectra's colour is integrated over: the scene's sample range.
std::pair<int, int> colourRange(const Scene &scene) {
  const std::vector<double> &w = scene.spectral.wavelengths;
  return {int(std::ceil(w.front())), int(std::floor(w.back()))};
}

Bands colourOf(const SampledSpectrum &spectrum, const Scene &scene, const Matrix3 &adaptation) {
  auto [first, last] = colourRange(scene);
  Vec3 rgb = xyzToLinearSrgb(adaptation * spectrumToXyz(spectrum, first, last));
  return Bands(rgb.x, rgb.y, rgb.z);
}

Bands clamped(Bands b, double maximum) {
  for (int i = 0; i < kBandCount; ++i) b[i] = std::clamp(b[i], 0.0, maximum);
  return b;
}

/// A light's spectrum as the renderers see it: its values at the scene's
/// sample wavelengths, linear between them (docs/spectral.md "Colour").
SampledSpectrum atSampleWavelengths(const SampledSpectrum &spectrum, const Scene &scene) {
  SampledSpectrum sampled{scene.spectral.wavelengths, {}};
  for (double nm : sampled.wavelengths) sampled.values.push_back(spectrum.at(nm));
  return sampled;
}

/// W·sr⁻¹ per candela of a spectral light: its spectrum scaled so that
/// 683 lm/W × its luminance weight over the scene's samples is 1 (light.h).
/// 0 when the spectrum has no luminance.
double wattsPerCandelaScale(const SampledSpectrum &spectrum, const Scene &scene) {
  auto [first, last] = colourRange(scene);
  const double y = spectrumToXyz(atSampleWavelengths(spectrum, scene), first, last).y;
  return y > 0 ? 1.0 / (kLuminousEfficacy * y) : 0.0;
}

}  // namespace

void applySpectralPass(Scene &scene, int pass) {
  auto atPass = [&](const SampledSpectrum &s) {
    Bands b;
    for (int i = 0; i < kBandCount; ++i) b[i] = s.at(scene.spectral.wavelength(pass, i));
    return b;
  };
  for (Material &m : scene.materials) {
    if (m.spectra.diffuse) m.diffuse = atPass(*m.spectra.diffuse);
    if (m.spectra.specular) m.specular = atPass(*m.spectra.specular);
    if (m.spectra.emission) m.emission = atPass(*m.spectra.emission);
    if (m.spectra.transmittance) m.transmittance = atPass(*m.spectra.transmittance);
  }
  for (PointLight &light : scene.lights)
    if (light.spectrum) light.wattsPerCandela = atPass(*light.spectrum) * wattsPerCandelaScale(*light.spectrum, scene);
}

void applySpectralColour(Scene &scene, WhiteBalance balance) {
  if (!scene.spectral.enabled()) return;
  Matrix3 adaptation{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
  if (balance == WhiteBalance::EqualEnergy) {
    auto [first, last] = colourRange(scene);
    SampledSpectrum one{{double(first)}, {1.0}};
    adaptation = bradfordAdaptation(spectrumToXyz(one, first, last), kD65White);
  }
  // A reflectance of 1 or more would make radiosity diverge; the loader's checks allow < 1.
  constexpr double kMaximumReflectance = 0.999;
  for (Material &m : scene.materials) {
    if (m.spectra.diffuse) m.diffuse = clamped(colourOf(*m.spectra.diffuse, scene, adaptation), kMaximumReflectance);
    if (m.spectra.specular) m.specular = clamped(colourOf(*m.spectra.specular, scene, adaptation), 1.0);
    if (m.spectra.emission) m.emission = clamped(colourOf(*m.spectra.emission, scene, adaptation), HUGE_VAL);
    if (m.spectra.transmittance)
      m.transmittance = clamped(colourOf(*m.spectra.transmittance, scene, adaptation), kMaximumReflectance);
    if (m.isTranslucent())  // keep ρ + τ below 1 after clamping each
      for (int i = 0; i < kBandCount; ++i)
        m.transmittance[i] = std::min(m.transmittance[i], kMaximumReflectance - m.diffuse[i]);
    if (m.kind == MaterialKind::Glossy)  // keep ρd + ρs ≤ 1 after clamping each
      for (int i = 0; i < kBandCount; ++i) m.diffuse[i] = std::min(m.diffuse[i], 1.0 - m.specular[i]);
  }
  // A light's colour keeps its photometry: candela × colour / (683 Y(colour)).
  for (PointLight &light : scene.lights) {
    if (!light.spectrum) continue;
    const Bands colour = clamped(colourOf(atSampleWavelengths(*light.spectrum, scene), scene, adaptation), HUGE_VAL);
    const double y = colour.luminance();
    light.wattsPerCandela = y > 0 ? colour / (kLuminousEfficacy * y) : Bands(0.0);
  }
}

void convertToRgbScene(Scene &scene, WhiteBalance balance) {
  applySpectralColour(scene, balance);
  for (Material &m : scene.materials) m.spectra = {};
  for (PointLight &light : scene.lights) light.spectrum.reset();
  scene.spectral = {};
}

BandColourMatching bandColourMatching(const Scene &scene) {
  return BandColourMatching(scene.spectral.wavelengths);
}

std::string passWavelengthLabel(const Scene &scene, int pass) {
  double first = scene.spectral.wavelength(pass, 0), last = scene.spectral.wavelength(pass, kBandCount - 1);
  return first == last ? fmt::format("{:g} nm", first) : fmt::format("{:g}–{:g} nm", first, last);
}

bool passHasEmission(const Scene &scene, int pass) {
  for (const PointLight &light : scene.lights) {
    if (!light.spectrum) return true;
    for (int i = 0; i < kBandCount; ++i)
      if (light.spectrum->at(scene.spectral.wavelength(pass, i)) > 0) return true;
  }
  for (const Material &m : scene.materials) {
    if (!m.spectra.emission) {
      if (m.isEmitter()) return true;
      continue;
    }
    for (int i = 0; i < kBandCount; ++i)
      if (m.spectra.emission->at(scene.spectral.wavelength(pass, i)) > 0) return true;
  }
  return false;
}

}  // namespace radiant
