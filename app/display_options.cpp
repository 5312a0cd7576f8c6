#include "display_options.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "render/emitter_coverage.h"
#include "util/error.h"

namespace radiant {

namespace {

/// Operator-parameter flags: each belongs to the operators whose registry entry lists it.
const char *const kParameterFlags[] = {
    "--exposure", "--key", "--reflected-level", "--display-max", "--display-contrast", "--adaptation", "--white"};
const char *const kOtherDisplayFlags[] = {"--tonemap", "--gamma", "--srgb", "--bits", "--gamut"};

std::string operatorsUsing(const std::string &flag) {
  std::string names;
  for (const ToneOperatorInfo &info : toneOperatorRegistry())
    for (const std::string &f : info.parameterFlags)
      if (f == flag) names += names.empty() ? info.name : std::string(", ") + info.name;
  return names;
}

std::string lowerExtension(const std::string &path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char &c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}
bool isPng(const std::string &path) {
  return lowerExtension(path) == ".png";
}

}  // namespace

void addDisplayOptions(CLI::App &app, DisplayCommandOptions &o) {
  std::string names;
  for (const ToneOperatorInfo &info : toneOperatorRegistry())
    names += fmt::format("\n  {:<18} {}", info.name, info.summary);
  app.add_option("--tonemap", o.toneOperator, "Tone operator (docs/tone-mapping.md):" + names)->default_val("linear");
  app.add_option("--exposure", o.exposure,
                 "linear: exposure in stops (radiance × 2^stops), or 'auto' (log-average luminance shown at --key)");
  app.add_option("--key", o.key, "linear --exposure auto, reinhard, aces: display value of the log-average luminance")
      ->default_val(0.18)
      ->check(CLI::PositiveNumber);
  app.add_option("--reflected-level", o.reflectedLevel,
                 "max-reflected: display value of the brightest non-emitting pixel")
      ->default_val(0.95)
      ->check(CLI::Range(1e-6, 1.0));
  app.add_option("--display-max", o.displayMax,
                 "tumblin-rushmeier (86), ward (100): the display's maximum luminance L_dmax = k, cd/m²")
      ->check(CLI::PositiveNumber);
  app.add_option("--display-contrast", o.displayContrast, "tumblin-rushmeier: the display's contrast ratio C_max")
      ->default_val(35)
      ->check(CLI::Range(1.000001, 1e9));
  app.add_option("--adaptation", o.adaptation,
                 "tumblin-rushmeier, ward: world adaptation luminance in cd/m² (default from the image)")
      ->check(CLI::PositiveNumber);
  app.add_option("--white", o.white, "reinhard: world luminance shown as full white, cd/m² (default: none)")
      ->check(CLI::PositiveNumber);
  CLI::Option *gamma =
      app.add_option("--gamma", o.gamma, "Transfer curve V = (I/k)^(1/G) of a display I = k·V^G instead of sRGB")
          ->check(CLI::Range(0.1, 10.0));
  CLI::Option *srgb = app.add_flag("--srgb", o.srgb, "Transfer curve: sRGB (the default)");
  gamma->excludes(srgb);
  app.add_option("--bits", o.bits, "PNG bits per channel, 8 or 16")->default_val(8)->check(CLI::IsMember({8, 16}));
  app.add_option("--gamut", o.gamut,
                 "Colours beyond full scale: clip each channel (clip), or divide by the largest channel, keeping the "
                 "hue (hue)")
      ->default_val("clip")
      ->check(CLI::IsMember({"clip", "hue"}));
}

DisplaySettings displaySettings(const CLI::App &app, const DisplayCommandOptions &o, double defaultExposureStops) {
  const ToneOperatorInfo &info = findToneOperator(o.toneOperator);
  for (const char *flag : kParameterFlags) {
    if (app.count(flag) == 0) continue;
    bool used = false;
    for (const std::string &f : info.parameterFlags) used = used || f == flag;
    if (!used)
      throw InputError(InputLocation{flag},
                       fmt::format("only {} use{} it, not --tonemap {}", operatorsUsing(flag),
                                   operatorsUsing(flag).find(',') == std::string::npos ? "s" : "", info.name));
  }
  DisplaySettings s;
  s.toneOperator = info.name;
  ToneParameters &p = s.parameters;
  p.exposureStops = defaultExposureStops;
  if (o.exposure == "auto") {
    p.autoExposure = true;
  } else if (!o.exposure.empty()) {
    size_t used = 0;
    try {
      p.exposureStops = std::stod(o.exposure, &used);
    } catch (const std::exception &) {
      used = 0;
    }
    if (used != o.exposure.size() || !std::isfinite(p.exposureStops))
      throw InputError(InputLocation{"--exposure"}, "expected a number of stops or 'auto', got '" + o.exposure + "'");
  }
  if (info.name == std::string("linear") && app.count("--key") > 0 && !p.autoExposure)
    throw InputError(InputLocation{"--key"}, "linear uses it only with --exposure auto");
  p.key = o.key;
  p.reflectedLevel = o.reflectedLevel;
  p.displayMaxCdM2 = o.displayMax;
  p.displayContrast = o.displayContrast;
  p.adaptationCdM2 = o.adaptation;
  p.whiteCdM2 = o.white;
  if (o.gamma) {
    s.transfer = TransferCurve::Gamma;
    s.gamma = *o.gamma;
  }
  s.bits = o.bits;
  s.gamut = o.gamut == "hue" ? GamutRule::Hue : GamutRule::Clip;
  return s;
}

DisplaySettings renderDisplaySettings(const CLI::App &app, const DisplayCommandOptions &options,
                                      double sceneExposureStops, const std::vector<std::string> &outputs) {
  DisplaySettings settings = displaySettings(app, options, sceneExposureStops);
  if (std::any_of(outputs.begin(), outputs.end(), isPng)) return settings;
  for (const char *flag : kParameterFlags)
    if (app.count(flag) > 0) throw InputError(InputLocation{flag}, "applies to .png outputs, and none is requested");
  for (const char *flag : kOtherDisplayFlags)
    if (app.count(flag) > 0) throw InputError(InputLocation{flag}, "applies to .png outputs, and none is requested");
  return settings;
}

void reportDisplayMapping(const DisplayMapping &mapping, bool describe) {
  if (describe) fmt::print(stderr, "radiant: {}\n", mapping.describe());
  for (const std::string &warning : mapping.warnings()) fmt::print(stderr, "radiant: warning: {}\n", warning);
}

void writeRenderOutputs(Image &image, const std::vector<std::string> &outputs, const DisplaySettings &display,
                        bool describeDisplay, const RayTracer &tracer, const PinholeCamera &camera, bool quiet) {
  bool png = false, exr = false;
  for (const std::string &path : outputs) {
    png = png || isPng(path);
    exr = exr || lowerExtension(path) == ".exr";
  }
  if (image.quantity.empty()) image.quantity = "radiance";
  if (exr || (png && display.toneOperator == "max-reflected"))
    image.emitterFraction = emitterCoverage(tracer, camera, image.width, image.height);
  std::optional<DisplayMapping> mapping;
  if (png) {
    mapping.emplace(image, display);
    if (!quiet) reportDisplayMapping(*mapping, describeDisplay);
  }
  for (const std::string &path : outputs) {
    if (isPng(path))
      mapping->writePng(image, path);
    else
      writeImage(image, path);
  }
}

}  // namespace radiant
