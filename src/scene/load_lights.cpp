// "lights" and "luminaires" of JSON scenes (docs/luminaires.md).
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <memory>
#include <utility>

#include "scene/light.h"
#include "scene/load_detail.h"

namespace radiant::detail {

namespace {

/// The largest intensity or flux accepted: beyond any real source (a
/// lighthouse is ~10⁷ cd), small enough that the watts stay finite.
constexpr double kMaxCandela = 1e12;

std::string uniqueLightName(LightNames &names, const JsonNode &node, const std::string &fallback) {
  const std::string name = node.string("name", fallback);
  if (name.empty()) node.child("name").fail("a light's name cannot be empty");
  if (names.find(name) >= 0) {
    if (node.has("name")) node.child("name").fail("a second light named '" + name + "'");
    node.fail("a second light named '" + name + "' (its default name): give it a \"name\"");
  }
  return name;
}

Vec3 lightPosition(const JsonNode &node, double metres) {
  const Vec3 p = node.child("position").asVec3() * metres;
  if (!withinCoordinateRange(p)) node.child("position").fail(fmt::format("beyond ±{:g} m", kMaxCoordinateMetres));
  return p;
}

/// "aim" (default straight down, −y: JSON scenes are y-up) and "rotation" (degrees about it).
void lightFrame(PointLight &light, const JsonNode &node) {
  Vec3 aim{0, -1, 0};
  if (node.has("aim")) {
    aim = node.child("aim").asVec3();
    if (!(length(aim) > 0)) node.child("aim").fail("the aim has zero length");
  }
  const double rotation = node.number("rotation", 0.0);
  if (std::abs(rotation) > 3600) node.child("rotation").fail("expected a rotation in degrees within ±3600");
  setLightFrame(light, aim, rotation);
}

/// "colour": three numbers (RGB scenes), one number (grey) or a spectrum
/// (spectral scenes); only its chromaticity matters (light.h), so its
/// luminance must be > 0.
void lightColour(PointLight &light, const JsonNode &node, bool spectralScene) {
  std::optional<SampledSpectrum> spectrum;
  const Bands colour = parseBandValue(node, "colour", Bands(1.0), spectralScene, spectrum);
  if (spectrum) {
    if (!spectralScene)
      node.child("colour").fail("a spectrum needs a spectral scene: add a \"spectral\" block (docs/spectral.md)");
    for (size_t i = 0; i < spectrum->values.size(); ++i)
      if (!(spectrum->values[i] >= 0) || !std::isfinite(spectrum->values[i]))
        node.child("colour").fail(fmt::format("the spectrum's value at {} nm is {}; expected a finite value ≥ 0",
                                              spectrum->wavelengths[i], spectrum->values[i]));
    light.spectrum = spectrum;
    return;  // wattsPerCandela is set per pass (applySpectralPass) or from its colour (applySpectralColour)
  }
  for (int b = 0; b < kBandCount; ++b)
    if (colour[b] < 0) node.child("colour").fail("expected colour values ≥ 0");
  const double luminance = colour.luminance();
  if (!(luminance > 0)) node.child("colour").fail("the colour has no luminance: a light of it would give no candela");
  // In a spectral scene a grey light is a constant spectrum, normalised like any other.
  if (spectralScene) light.spectrum = SampledSpectrum{{550.0}, {1.0}};
  light.wattsPerCandela = colour / (kLuminousEfficacy * luminance);
}

double positiveAmount(const JsonNode &node, const std::string &key, const char *unit) {
  const double v = node.child(key).asNumber();
  if (!(v >= 0) || v > kMaxCandela) node.child(key).fail(fmt::format("expected {} from 0 to {:g}", unit, kMaxCandela));
  return v;
}

/// "size": [length, width] (along C0 and C90) or "diameter": the luminous
/// opening of a luminaire on an area; "area_samples": the lattice's side.
void parseOpening(PointLight &light, const JsonNode &node, double metres) {
  if (node.has("size") && node.has("diameter")) node.fail("give the opening's \"size\" or its \"diameter\", not both");
  if (node.has("size")) {
    std::vector<JsonNode> size = node.child("size").asArray(2, 2);
    const double length = size[0].asNumber() * metres, width = size[1].asNumber() * metres;
    if (!(length > 0 && width > 0 && length <= 1e3 && width <= 1e3))
      node.child("size").fail("expected [length, width], each > 0 and at most 1000 m");
    light.halfLength = length / 2, light.halfWidth = width / 2;
  } else if (node.has("diameter")) {
    const double diameter = node.child("diameter").asNumber() * metres;
    if (!(diameter > 0 && diameter <= 1e3)) node.child("diameter").fail("expected a diameter > 0, at most 1000 m");
    light.halfLength = light.halfWidth = diameter / 2;
    light.round = true;
  }
  if (node.has("area_samples") && !light.isArea())
    node.child("area_samples").fail("only a luminaire with a \"size\" or \"diameter\" has an area to sample");
  light.lattice = light.isArea() ? static_cast<int>(node.integer("area_samples", 4, 1, 32)) : 1;
}

}  // namespace

void parseLights(Scene &scene, const JsonNode &lights, double metres) {
  std::vector<JsonNode> entries = lights.asArray();
  LightNames names(scene.lights);
  for (size_t index = 0; index < entries.size(); ++index) {
    const JsonNode &node = entries[index];
    node.expectObject();
    const std::string type = node.child("type").asString();
    PointLight light;
    light.definedAt = node.location();
    if (type == "point") {
      node.checkKeys({"type", "name", "position", "intensity", "lumens", "colour"});
      light.kind = PointLightKind::Point;
    } else if (type == "spot") {
      node.checkKeys({"type", "name", "position", "aim", "rotation", "intensity", "lumens", "colour", "cone_angle",
                      "falloff_angle"});
      light.kind = PointLightKind::Spot;
    } else {
      node.child("type").fail("unknown light type '" + type + "'; known: point, spot" +
                              didYouMean(type, {"point", "spot"}) + " (photometric files go in \"luminaires\")");
    }
    light.name = uniqueLightName(names, node, fmt::format("{}-{}", type, index));
    light.position = lightPosition(node, metres);
    lightFrame(light, node);
    if (light.kind == PointLightKind::Spot) {
      // cone_angle: the full angle of the outer cone (no light beyond);
      // falloff_angle: how much of it, at its edge, fades (0: a hard edge).
      const double cone = node.number("cone_angle", 60.0);
      if (!(cone >= 0.1 && cone <= 180))
        node.child("cone_angle").fail("expected a full cone angle from 0.1 to 180 degrees");
      const double falloff = node.number("falloff_angle", 0.0);
      if (!(falloff >= 0 && falloff <= cone / 2))
        node.child("falloff_angle")
            .fail(fmt::format("expected a falloff from 0 to half the cone angle, {}°", cone / 2));
      const double outer = cone / 2, inner = outer - falloff;
      light.cosOuter = std::cos(outer * kPi / 180.0);
      light.cosInner = std::cos(inner * kPi / 180.0);
      if (light.cosInner <= light.cosOuter) light.cosInner = std::nextafter(light.cosOuter, 2.0);
    }
    if (node.has("intensity") == node.has("lumens"))
      node.fail("give the light's \"intensity\" (cd) or its \"lumens\" (lm), one of them");
    if (node.has("intensity")) {
      light.candela = positiveAmount(node, "intensity", "an intensity in cd");
    } else {
      light.candela = 1.0;
      const double perCandela = light.lumens();
      light.candela = positiveAmount(node, "lumens", "a flux in lm") / perCandela;
    }
    lightColour(light, node, scene.spectral.enabled());
    scene.lights.push_back(std::move(light));
  }
}

void parseLuminaires(Scene &scene, const JsonNode &luminaires, double metres, const std::filesystem::path &directory) {
  std::vector<JsonNode> entries = luminaires.asArray();
  LightNames names(scene.lights);
  // A file named by many luminaires (a ceiling of one downlight) is read and
  // tabulated once; the distribution is immutable and shared.
  std::map<std::pair<std::string, bool>, std::shared_ptr<const PhotometricDistribution>> distributions;
  for (size_t index = 0; index < entries.size(); ++index) {
    const JsonNode &node = entries[index];
    node.expectObject();
    node.checkKeys({"name", "ies", "ldt", "position", "aim", "rotation", "multiplier", "colour", "size", "diameter",
                    "area_samples"});
    PointLight light;
    light.kind = PointLightKind::Photometric;
    light.definedAt = node.location();
    if (node.has("ies") == node.has("ldt"))
      node.fail("give the luminaire's photometric file as \"ies\" (IES LM-63) or \"ldt\" (EULUMDAT), one of them");
    const JsonNode file = node.child(node.has("ies") ? "ies" : "ldt");
    const std::string path = (directory / file.asString()).string();
    const bool asIes = node.has("ies");
    auto &distribution = distributions[{path, asIes}];
    if (!distribution) {
      // The key says what the file is; its content decides (a .ldt renamed, or named under the other key).
      const PhotometricFormat format = photometricFormatOfFile(path);
      if (asIes && format == PhotometricFormat::Eulumdat)
        file.fail("this is a EULUMDAT file: give it as \"ldt\" ('" + path + "')");
      if (!asIes && format == PhotometricFormat::Ies)
        file.fail("this is an IES LM-63 file: give it as \"ies\" ('" + path + "')");
    }
    try {
      if (!distribution) distribution = asIes ? readIesFile(path) : readEulumdatFile(path);
      light.photometry = distribution;
    } catch (const InputError &e) {
      // The file's own error names its line; say which luminaire asked for it.
      throw InputError(e.location(), e.message() + fmt::format(" (the photometric file of {})", file.path()));
    }
    light.name = uniqueLightName(names, node, fmt::format("luminaire-{}", index));
    light.position = lightPosition(node, metres);
    lightFrame(light, node);
    light.multiplier = node.number("multiplier", 1.0);
    // IES TILT: the lamp's output at the luminaire's tilt from straight down (−y).
    const double tilt = std::acos(std::clamp(-light.axis.y, -1.0, 1.0)) * 180.0 / kPi;
    const double tiltFactor = light.photometry->tiltFactor(tilt);
    if (!(light.multiplier >= 0) || light.multiplier * tiltFactor * light.photometry->maxCandela() > kMaxCandela)
      node.child("multiplier")
          .fail(fmt::format("expected a multiplier ≥ 0 that keeps the intensity under {:g} cd", kMaxCandela));
    light.multiplier *= tiltFactor;
    lightColour(light, node, scene.spectral.enabled());
    parseOpening(light, node, metres);
    scene.lights.push_back(std::move(light));
  }
}

}  // namespace radiant::detail
