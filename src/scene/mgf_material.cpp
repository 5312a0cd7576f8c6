// MGF colours and materials → Radiant (docs/scene-format.md#mgf-materials).
//
// MGF gives every reflectance, transmittance and emittance as an amount (a
// luminous fraction, or lm/m² for `ed`) times a colour of unit luminance
// (Ward, "The Materials and Geometry Format", §Color and §Material). A colour
// is a CIE (x, y) chromaticity or a spectrum over 380–780 nm (cspec, cct,
// cmix); Radiant takes its linear sRGB with the equal-energy white shown as
// grey (Bradford adaptation to D65, docs/spectral.md), so that MGF's default
// neutral colour leaves a reflectance grey.

#include <algorithm>
#include <cmath>
#include <sstream>

#include "scene/mgf_detail.h"

namespace radiant::detail {

namespace {

bool sameColour(const MgfColour &a, const MgfColour &b) {
  if (a.x != b.x || a.y != b.y || a.spectrum.has_value() != b.spectrum.has_value()) return false;
  return !a.spectrum ||
         (a.spectrum->wavelengths == b.spectrum->wavelengths && a.spectrum->values == b.spectrum->values);
}

}  // namespace

bool sameMgfValues(const MgfMaterial &a, const MgfMaterial &b) {
  return a.sides == b.sides && a.rd == b.rd && a.td == b.td && a.ed == b.ed && a.rs == b.rs && a.rsAlpha == b.rsAlpha &&
         a.ts == b.ts && a.tsAlpha == b.tsAlpha && a.iorReal == b.iorReal && a.iorImaginary == b.iorImaginary &&
         sameColour(a.rdColour, b.rdColour) && sameColour(a.tdColour, b.tdColour) &&
         sameColour(a.edColour, b.edColour) && sameColour(a.rsColour, b.rsColour) && sameColour(a.tsColour, b.tsColour);
}
namespace {

/// Lumens per watt of the equal-energy white at 555 nm's peak efficacy, the
/// constant that relates Radiant's emission units to cd/m² (docs/spectral.md#units).
constexpr double kLuminousEfficacy = 683.0;
/// The range over which MGF colours are defined and normalised.
constexpr int kMgfFirstNm = 380, kMgfLastNm = 780;

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

/// Normalises a spectrum to luminance 1 over 380–780 nm and records its chromaticity.
MgfColour colourOfSpectrum(SampledSpectrum spectrum, const InputLocation &where) {
  const Vec3 xyz = spectrumToXyz(spectrum, kMgfFirstNm, kMgfLastNm);
  if (!(xyz.y > 0) || !std::isfinite(xyz.y))
    throw InputError(where, "the colour's spectrum has no luminance between 380 and 780 nm");
  for (double &v : spectrum.values) v /= xyz.y;
  MgfColour colour;
  const double sum = xyz.x + xyz.y + xyz.z;
  colour.x = xyz.x / sum;
  colour.y = xyz.y / sum;
  colour.spectrum = std::move(spectrum);
  return colour;
}

}  // namespace

MgfColour mgfColourFromChromaticity(double x, double y, const InputLocation &where) {
  // y = 0 is on the diagram's edge (MGF's parser accepts it) but has no
  // luminance: such a colour is black (the reader warns).
  if (!(x >= 0 && y >= 0 && x + y <= 1))
    throw InputError(
        where, "cxy " + number(x) + " " + number(y) + " is not a chromaticity: expected x ≥ 0, y ≥ 0 and x + y ≤ 1");
  MgfColour colour;
  colour.x = x;
  colour.y = y;
  return colour;
}

MgfColour mgfColourFromSpectrum(double firstNm, double lastNm, const std::vector<double> &values,
                                const InputLocation &where) {
  if (!(firstNm > 0 && lastNm > firstNm && lastNm < 2000))
    throw InputError(where, "cspec needs 0 < λmin < λmax (nm), got " + number(firstNm) + " and " + number(lastNm));
  if (values.size() < 2) throw InputError(where, "cspec needs at least two values");
  SampledSpectrum spectrum;
  // Zero outside [λmin, λmax] (the specification's convention), where
  // SampledSpectrum would hold its end values.
  spectrum.wavelengths.push_back(firstNm - 1e-3);
  spectrum.values.push_back(0);
  const double step = (lastNm - firstNm) / double(values.size() - 1);
  for (size_t i = 0; i < values.size(); ++i) {
    if (!(values[i] >= 0) || !std::isfinite(values[i]))
      throw InputError(
          where, "cspec value " + std::to_string(i + 1) + " is " + number(values[i]) + ": expected a finite value ≥ 0");
    spectrum.wavelengths.push_back(firstNm + step * double(i));
    spectrum.values.push_back(values[i]);
  }
  spectrum.wavelengths.push_back(lastNm + 1e-3);
  spectrum.values.push_back(0);
  return colourOfSpectrum(std::move(spectrum), where);
}

MgfColour mgfColourFromTemperature(double kelvin, const InputLocation &where) {
  if (!(kelvin >= 500 && kelvin <= 1e6))
    throw InputError(where, "cct " + number(kelvin) + ": expected a temperature from 500 to 10⁶ K");
  // Planck's law; constants cancel in the normalisation except c2 = hc/k.
  constexpr double kC2 = 1.4387769e-2;  // m·K
  SampledSpectrum spectrum;
  for (int nm = kMgfFirstNm; nm <= kMgfLastNm; nm += 5) {
    const double metres = nm * 1e-9;
    spectrum.wavelengths.push_back(nm);
    spectrum.values.push_back(1.0 / (std::pow(metres, 5) * std::expm1(kC2 / (metres * kelvin))));
  }
  return colourOfSpectrum(std::move(spectrum), where);
}

MgfColour mgfColourMix(const std::vector<std::pair<double, MgfColour>> &parts, const InputLocation &where) {
  // Each part has luminance 1, so a weight is the part's luminance in the mix:
  // XYZ = Σ wᵢ XYZᵢ (what MGF's parser does by weighting chromaticities by w/y).
  Vec3 xyz{0, 0, 0};
  double total = 0;
  bool allSpectral = true;
  for (const auto &[weight, colour] : parts) {
    if (!(weight >= 0) || !std::isfinite(weight))
      throw InputError(where, "cmix weight " + number(weight) + ": expected a finite weight ≥ 0");
    if (colour.y <= 0) continue;  // black
    xyz = xyz + Vec3{colour.x / colour.y, 1.0, (1 - colour.x - colour.y) / colour.y} * weight;
    total += weight;
    allSpectral = allSpectral && colour.spectrum.has_value();
  }
  if (!(total > 0) || !(xyz.y > 0))
    throw InputError(where, "cmix needs a weight above 0 on a colour that is not black");
  if (allSpectral) {
    SampledSpectrum spectrum;
    for (int nm = kMgfFirstNm; nm <= kMgfLastNm; nm += 5) {
      double value = 0;
      for (const auto &[weight, colour] : parts) value += weight * colour.spectrum->at(nm);
      spectrum.wavelengths.push_back(nm);
      spectrum.values.push_back(value);
    }
    return colourOfSpectrum(std::move(spectrum), where);
  }
  MgfColour colour;
  const double sum = xyz.x + xyz.y + xyz.z;
  colour.x = xyz.x / sum;
  colour.y = xyz.y / sum;
  return colour;
}

Bands mgfColourToLinearSrgb(const MgfColour &colour, bool &clipped) {
  static const Matrix3 kAdapt = bradfordAdaptation(Vec3{1, 1, 1}, kD65White);
  clipped = false;
  if (colour.y <= 0) return Bands(0.0);
  const Vec3 xyz{colour.x / colour.y, 1.0, (1 - colour.x - colour.y) / colour.y};
  Vec3 rgb = xyzToLinearSrgb(kAdapt * xyz);
  clipped = rgb.x < -1e-9 || rgb.y < -1e-9 || rgb.z < -1e-9;
  rgb = Vec3{std::max(rgb.x, 0.0), std::max(rgb.y, 0.0), std::max(rgb.z, 0.0)};
  // Bradford adaptation keeps a colour's luminance only roughly (5 % off for
  // a saturated green), and clipping to the gamut changes it too: set it back
  // to 1, so that `rd 0.2` reflects 20 % of the light whatever its colour.
  const double luminance = 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z;
  if (luminance > 0) rgb = rgb * (1 / luminance);
  return Bands(rgb.x, rgb.y, rgb.z);
}

Material mgfToMaterial(const MgfMaterial &mgf, const std::string &name, const InputLocation &where,
                       std::vector<std::string> &warnings, bool spectral) {
  const std::string prefix = where.toString() + ": material '" + name + "': ";
  bool anyClipped = false;
  auto bands = [&](double amount, const MgfColour &colour) {
    bool clipped = false;
    Bands b = mgfColourToLinearSrgb(colour, clipped);
    anyClipped = anyClipped || (clipped && amount > 0);
    b *= amount;
    return b;
  };
  Material m;
  m.name = name;
  m.definedAt = where;
  m.diffuse = bands(mgf.rd, mgf.rdColour);
  // ed is luminous exitance in lm/m²; a Lambertian emitter's luminance is
  // ed/π cd/m², and Radiant's emission v has luminance 683·v cd/m².
  m.emission = bands(mgf.ed / (kPi * kLuminousEfficacy), mgf.edColour);
  if (mgf.ts > 0) {
    m.kind = MaterialKind::Dielectric;
    m.ior = mgf.iorReal > 0 ? mgf.iorReal : 1.0;
    m.specular = bands(mgf.ts, mgf.tsColour);
    // ts's α, like rs's, is read as GGX's α: rough glass (Walter et al. 2007).
    // With no ir (ior 1, a thin sheet) it changes nothing: an index of 1 bends no ray.
    if (mgf.tsAlpha > 0) m.transmissionRoughness = std::clamp(mgf.tsAlpha, 0.01, 1.0);
    if (mgf.rd > 0 || mgf.rs > 0)
      warnings.push_back(prefix + "specular transmittance (ts) makes it " +
                         (m.isRoughDielectric() ? "rough" : "smooth") + " glass (ior " + number(m.ior) +
                         "): its rd and rs are dropped, the glass reflects by Fresnel's law");
    m.diffuse = Bands(0.0);
  } else if (mgf.rs > 0) {
    m.specular = bands(mgf.rs, mgf.rsColour);
    if (mgf.rsAlpha <= 0 && mgf.rd <= 0) {
      m.kind = MaterialKind::Mirror;
      m.diffuse = Bands(0.0);
    } else {
      // MGF's α is the RMS facet slope of Ward's model; it is used as GGX's α,
      // which has the same meaning for small slopes. A smooth specular part
      // over a diffuse base becomes a very sharp glossy lobe.
      m.kind = MaterialKind::Glossy;
      m.roughness = std::clamp(mgf.rsAlpha, 0.01, 1.0);
    }
  }
  if (mgf.td > 0) {
    if (m.kind == MaterialKind::Lambertian || m.kind == MaterialKind::Glossy) {
      // Light goes through to the back, which must then be part of the
      // solution: a translucent surface is two-sided whatever its `sides`.
      m.transmittance = bands(mgf.td, mgf.tdColour);
      m.twoSided = true;
    } else {
      warnings.push_back(prefix + "diffuse transmittance (td " + number(mgf.td) + ") is dropped: it applies to " +
                         "diffuse materials, and this one is " + materialKindName(m.kind));
    }
  }
  if (mgf.sides == 2) {
    if (m.kind == MaterialKind::Dielectric)
      warnings.push_back(prefix +
                         "'sides 2' is dropped: a transmitting (ts) material is glass, the "
                         "interface between inside and outside, whose faces are one-sided");
    else
      m.twoSided = true;
  }
  if (anyClipped)
    warnings.push_back(prefix + "a colour outside the sRGB gamut was clipped to it (negative components set to 0)");

  // ρ ≥ 1 makes radiosity diverge: scale the reflectances down keeping their
  // colour and ratio, as the MTL reader does.
  double scatter = 0;
  for (int b = 0; b < kBandCount; ++b) {
    const double sum = (m.kind == MaterialKind::Glossy || m.kind == MaterialKind::Lambertian)
                           ? m.diffuse[b] + m.specular[b] + m.transmittance[b]
                           : m.specular[b];
    scatter = std::max(scatter, sum);
  }
  double factor = 1;
  // Slightly below 1/scatter, so that rounding cannot leave a sum above 1.
  if (scatter > 1) factor = (1 - 1e-12) / scatter;
  const double diffuseScatter = (m.diffuse + m.transmittance).max();
  if (diffuseScatter * factor > kMaxDiffuseReflectance) factor = kMaxDiffuseReflectance / diffuseScatter;
  if (factor < 1) {
    m.diffuse *= factor;
    m.specular *= factor;
    m.transmittance *= factor;
  }
  // MGF files often give rd + rs = 1 exactly, which the neutral colour's
  // rounding (its sRGB is 1 ± 10⁻⁵) takes just above 1: not worth a warning.
  if (factor < 0.999) {
    warnings.push_back(prefix +
                       "reflects as much light as it receives or more in a colour band; its reflectances "
                       "are scaled by " +
                       number(factor));
  }
  if (spectral) {
    // The colour's spectrum times the amount (docs/spectral.md); a neutral
    // chromaticity is the constant spectrum, any other says too little.
    auto spectrumOf = [&](double amount, const MgfColour &colour,
                          const char *entity) -> std::optional<SampledSpectrum> {
      if (amount <= 0) return std::nullopt;
      SampledSpectrum s;
      if (colour.spectrum) {
        s = *colour.spectrum;
        for (double &v : s.values) v *= amount;
      } else if (std::abs(colour.x - 1.0 / 3) < 1e-4 && std::abs(colour.y - 1.0 / 3) < 1e-4) {
        s.wavelengths = {550};
        s.values = {amount};
      } else {
        throw InputError(where, "material '" + name + "': the colour of its '" + entity +
                                    "' is a chromaticity (cxy), which does not say what the spectrum is in this "
                                    "spectral scene; give it with cspec, cct or cmix of those");
      }
      return s;
    };
    const bool hasDiffuse = m.kind == MaterialKind::Lambertian || m.kind == MaterialKind::Glossy;
    if (hasDiffuse) m.spectra.diffuse = spectrumOf(mgf.rd * factor, mgf.rdColour, "rd");
    if (m.kind == MaterialKind::Dielectric) m.spectra.specular = spectrumOf(mgf.ts, mgf.tsColour, "ts");
    if (m.kind == MaterialKind::Mirror || m.kind == MaterialKind::Glossy)
      m.spectra.specular = spectrumOf(mgf.rs * factor, mgf.rsColour, "rs");
    m.spectra.emission = spectrumOf(mgf.ed / (kPi * kLuminousEfficacy), mgf.edColour, "ed");
    if (m.isTranslucent()) m.spectra.transmittance = spectrumOf(mgf.td * factor, mgf.tdColour, "td");
  }
  return m;
}

}  // namespace radiant::detail
