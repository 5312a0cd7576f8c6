// The JSON scene format's spectral values (docs/scene-format.md, "Spectral
// scenes"): the top-level "spectral" block and {"spectrum": …} material values.

#include <fmt/format.h>

#include <cmath>

#include "scene/load_detail.h"
#include "scene/spectral_scene.h"

namespace radiant::detail {

namespace {

/// Keys of a material whose value may be a spectrum, and the Material field each fills.
constexpr const char *kSpectralKeys[] = {"reflectance", "specular", "transmittance", "emission"};

/// Beyond this many samples a spectrum is more likely a mistake than a measurement.
constexpr size_t kMaximumSpectrumSamples = 100000;
constexpr size_t kMaximumSceneWavelengths = 300;

}  // namespace

SampledSpectrum parseSpectrum(const JsonNode &node) {
  node.checkKeys({"spectrum", "scale"});
  SampledSpectrum s;
  const double scale = node.number("scale", 1.0);
  if (scale < 0) node.child("scale").fail("a spectrum's scale must be ≥ 0");
  for (const JsonNode &sample : node.child("spectrum").asArray(1, kMaximumSpectrumSamples)) {
    std::vector<JsonNode> pair = sample.asArray(2, 2);
    double wavelength = pair[0].asNumber(), value = pair[1].asNumber();
    if (!(wavelength > 0)) pair[0].fail(fmt::format("wavelength {} nm must be positive", wavelength));
    if (!s.wavelengths.empty() && wavelength <= s.wavelengths.back())
      pair[0].fail(fmt::format("wavelengths must increase: {} nm follows {} nm", wavelength, s.wavelengths.back()));
    s.wavelengths.push_back(wavelength);
    s.values.push_back(value * scale);
  }
  return s;
}

SpectralSettings defaultSpectralSettings() {
  SpectralSettings settings;
  for (int nm = 400; nm <= 700; nm += 20) settings.wavelengths.push_back(nm);
  return settings;
}

SpectralSettings parseSpectralSettings(const JsonNode &node) {
  node.checkKeys({"wavelengths", "range", "samples"});
  SpectralSettings settings;
  const std::string where =
      fmt::format("between {} and {} nm (the CIE 1931 table)", kCieFirstWavelength, kCieLastWavelength);
  if (node.has("wavelengths")) {
    if (node.has("range") || node.has("samples"))
      node.fail("give either \"wavelengths\" or \"range\" with \"samples\", not both");
    JsonNode list = node.child("wavelengths");
    for (const JsonNode &w : list.asArray(3, kMaximumSceneWavelengths)) {
      double nm = w.asNumber();
      if (nm < kCieFirstWavelength || nm > kCieLastWavelength)
        w.fail(fmt::format("wavelength {} nm must lie {}", nm, where));
      if (!settings.wavelengths.empty() && nm <= settings.wavelengths.back())
        w.fail(fmt::format("wavelengths must increase: {} nm follows {} nm", nm, settings.wavelengths.back()));
      settings.wavelengths.push_back(nm);
    }
    // Colour is integrated over the whole nm in [first, last] (the 1-nm CIE table).
    if (std::ceil(settings.wavelengths.front()) > std::floor(settings.wavelengths.back()))
      list.fail("the wavelengths must span at least one whole nm, over which colour is integrated");
    return settings;
  }
  JsonNode rangeNode = node.child("range");
  std::vector<JsonNode> range = rangeNode.asArray(2, 2);
  double first = range[0].asNumber(), last = range[1].asNumber();
  if (first < kCieFirstWavelength || last > kCieLastWavelength || !(first < last))
    rangeNode.fail(fmt::format("expected [first, last] with first < last, both {}", where));
  if (std::ceil(first) > std::floor(last))
    rangeNode.fail("the range must hold at least one whole nm, over which colour is integrated");
  auto samples = node.integer("samples", 16, 3, kMaximumSceneWavelengths);
  for (int64_t i = 0; i < samples; ++i) settings.wavelengths.push_back(first + (last - first) * i / (samples - 1));
  return settings;
}

bool materialsGiveSpectra(const JsonNode &materials) {
  if (!materials.isObject()) return false;
  for (const auto &[name, material] : materials.value().items())
    if (material.is_object())
      for (const char *key : kSpectralKeys)
        if (material.contains(key) && material[key].is_object()) return true;
  return false;
}

Bands parseBandValue(const JsonNode &material, const std::string &key, const Bands &fallback, bool spectralScene,
                     std::optional<SampledSpectrum> &spectrum) {
  if (!material.has(key)) return fallback;
  JsonNode node = material.child(key);
  if (node.isObject()) {
    spectrum = parseSpectrum(node);
    // A placeholder until applySpectralColour: 0 passes checkMaterial's band
    // checks, which a spectrum gets from checkSpectra (per sample) and
    // checkSpectralScene (glossy sums at the scene's wavelengths) instead.
    return Bands(0.0);
  }
  Bands b = node.asBands();
  if (spectralScene && (b[0] != b[1] || b[1] != b[2]))
    node.fail(
        "this scene is spectral, so an RGB colour has no meaning here: give a spectrum "
        "{\"spectrum\": [[nm, value], …]} or one number for a grey");
  return b;
}

void checkSpectra(const Material &m, const InputLocation &where, const MaterialFieldNames &names) {
  const std::string subject = "material '" + m.name + "': ";
  auto check = [&](const std::optional<SampledSpectrum> &spectrum, const char *field, double maximum, bool exclusive,
                   const char *why) {
    if (!spectrum) return;
    InputLocation at = where;
    at.jsonPath += std::string("/") + field;
    for (size_t i = 0; i < spectrum->values.size(); ++i) {
      double v = spectrum->values[i];
      std::string value = fmt::format("{} {} at {} nm", field, v, spectrum->wavelengths[i]);
      if (!std::isfinite(v)) throw InputError(at, subject + value + " is not finite");
      if (v < 0) throw InputError(at, subject + value + " is negative; expected ≥ 0");
      if (exclusive ? v >= maximum : v > maximum)
        throw InputError(at, subject + value + fmt::format(" must be {} {}", exclusive ? "<" : "≤", maximum) + why);
    }
  };
  check(m.spectra.diffuse, names.diffuse, 1.0, true, ": a diffuse reflectance of 1 or more makes radiosity diverge");
  check(m.spectra.specular, names.specular, 1.0, false, ": a surface cannot reflect more than it receives");
  check(m.spectra.emission, names.emission, HUGE_VAL, false, "");
  check(m.spectra.transmittance, names.transmittance, 1.0, true,
        ": a surface cannot pass on all the light it receives");
}

void checkSpectralScene(Scene &scene) {
  auto definedAt = [&](const Material &m) {
    return m.definedAt.file.empty() ? InputLocation{scene.sourceFile} : m.definedAt;
  };
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    Material &m = scene.materials[i];
    const InputLocation where = definedAt(m);
    for (const Bands *b : {&m.diffuse, &m.specular, &m.emission})
      if (!m.spectra.any() && ((*b)[0] != (*b)[1] || (*b)[1] != (*b)[2]))
        throw InputError(where, "material '" + m.name +
                                    "' has an RGB colour, but this scene is spectral: give its values as spectra in "
                                    "the scene's \"materials\" (a material of that name there overrides the MTL's)");
    // A grey value is the constant spectrum: held as one, it gets the same
    // colour as any other spectrum outside a pass (the equal-energy white's).
    auto constant = [&](std::optional<SampledSpectrum> &spectrum, const Bands &grey) {
      if (!spectrum && grey[0] > 0) spectrum = SampledSpectrum{{scene.spectral.wavelengths.front()}, {grey[0]}};
    };
    constant(m.spectra.diffuse, m.diffuse), constant(m.spectra.specular, m.specular);
    constant(m.spectra.emission, m.emission), constant(m.spectra.transmittance, m.transmittance);
    // Emission that falls between the scene's wavelengths is never sampled.
    if (m.spectra.emission) {
      double sampled = 0, given = 0;
      for (double nm : scene.spectral.wavelengths) sampled = std::max(sampled, m.spectra.emission->at(nm));
      for (double v : m.spectra.emission->values) given = std::max(given, v);
      if (given > 0 && sampled == 0)
        scene.warnings.push_back(
            fmt::format("material '{}' emits only between the scene's sample wavelengths: it is "
                        "dark in a spectral render (sample more densely, \"spectral\")",
                        m.name));
    }
  }
  // Each value lies in its range at its samples, so everywhere between; a
  // glossy sum of two spectra is checked where it is used, at the scene's wavelengths.
  for (int pass = 0; pass < scene.spectral.passCount(); ++pass) {
    applySpectralPass(scene, pass);
    for (size_t i = 0; i < scene.materials.size(); ++i) {
      const Material &m = scene.materials[i];
      if (m.isTranslucent() && m.spectra.any())
        for (int b = 0; b < kBandCount; ++b) {
          const double sum = m.diffuse[b] + m.transmittance[b] + (m.kind == MaterialKind::Glossy ? m.specular[b] : 0);
          if (m.diffuse[b] + m.transmittance[b] >= 1.0 || sum > 1.0)
            throw InputError(definedAt(m), fmt::format("material '{}': its reflectances and diffuse_transmittance add "
                                                       "up to {} at {} nm: the surface would scatter as much light "
                                                       "as it receives or more",
                                                       m.name, sum, scene.spectral.wavelength(pass, b)));
        }
      if (m.kind != MaterialKind::Glossy || !m.spectra.any()) continue;
      for (int b = 0; b < kBandCount; ++b)
        if (m.diffuse[b] + m.specular[b] > 1.0)
          throw InputError(definedAt(m),
                           fmt::format("material '{}': reflectance + specular = {} at {} nm exceeds 1: the surface "
                                       "would reflect more than it receives",
                                       m.name, m.diffuse[b] + m.specular[b], scene.spectral.wavelength(pass, b)));
    }
  }
  applySpectralColour(scene);
  // A light's candela are kept through its spectrum's luminance: a spectrum
  // with none at the scene's wavelengths would make it silently dark.
  for (const PointLight &light : scene.lights)
    if (light.spectrum && light.wattsPerCandela.max() <= 0)
      throw InputError(light.definedAt,
                       fmt::format("light '{}': its colour's spectrum has no luminance at the scene's wavelengths "
                                   "(it is 0 at every sample): its candela could not be kept",
                                   light.name));
}

}  // namespace radiant::detail
