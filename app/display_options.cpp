#include "display_options.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "render/emitter_coverage.h"
#include "util/error.h"
#include "util/file_extension.h"

namespace radiant {

namespace {

const char *const kOtherDisplayFlags[] = {"--tonemap", "--gamma", "--srgb", "--bits", "--gamut"};

bool isPng(const std::string &path) {
  return lowercaseExtension(path) == ".png";
}

}  // namespace

void addDisplayOptions(CLI::App &app, DisplayCommandOptions &o) {
  std::string names;
  for (const ToneOperatorInfo &info : toneOperatorRegistry())
    names += fmt::format("\n  {:<18} {}", info.name, info.summary);
  app.add_option("--tonemap", o.toneOperator, "Tone operator (docs/tone-mapping.md):" + names)->default_val("linear");
  std::vector<ParameterGroup> groups;
  for (const ToneOperatorInfo &info : toneOperatorRegistry())
    groups.push_back({fmt::format("--tonemap {}", info.name), &info.parameters});
  o.toneParameters.add(app, groups);
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

DisplaySettings displaySettings(const CLI::App &, const DisplayCommandOptions &o, double defaultExposureStops) {
  const ToneOperatorInfo &info = findToneOperator(o.toneOperator);
  DisplaySettings s;
  s.toneOperator = info.name;
  s.parameters = toneParameters(info, o.toneParameters.given(), defaultExposureStops);
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
  const ParameterValues given = options.toneParameters.given();
  for (const auto &[name, value] : given.all())
    throw InputError(value.origin, "applies to .png outputs, and none is requested");
  for (const char *flag : kOtherDisplayFlags)
    if (app.count(flag) > 0) throw InputError(InputLocation{flag}, "applies to .png outputs, and none is requested");
  return settings;
}

void reportDisplayMapping(const DisplayMapping &mapping, bool describe) {
  if (describe) fmt::print(stderr, "radiant: {}\n", mapping.describe());
  for (const std::string &warning : mapping.warnings()) fmt::print(stderr, "radiant: warning: {}\n", warning);
}

void writeRenderOutputs(Image &image, const std::vector<std::string> &outputs, const DisplaySettings &display,
                        bool describeDisplay, const RayTracer &tracer, const PinholeCamera &camera, bool quiet,
                        std::vector<float> *coverage) {
  bool png = false, exr = false;
  for (const std::string &path : outputs) {
    png = png || isPng(path);
    exr = exr || lowercaseExtension(path) == ".exr";
  }
  if (image.quantity.empty()) image.quantity = "radiance";
  if (exr || (png && display.toneOperator == "max-reflected")) {
    if (!coverage)
      image.emitterFraction = emitterCoverage(tracer, camera, image.width, image.height);
    else {
      if (coverage->empty()) *coverage = emitterCoverage(tracer, camera, image.width, image.height);
      image.emitterFraction = *coverage;
    }
  }
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
