// radiant tonemap IMAGE -o OUT.png — maps a saved linear image (render's EXR,
// absolute radiance) to a display PNG with any tone operator, or to a
// false-colour luminance map, without rendering again (docs/tone-mapping.md).
#include <fmt/format.h>

#include <filesystem>
#include <sstream>

#include "commands.h"
#include "display/display_mapping.h"
#include "display/false_colour.h"
#include "display/luminance.h"
#include "display_options.h"
#include "io/image.h"
#include "io/output_files.h"
#include "util/error.h"

namespace radiant {

namespace {

struct TonemapOptions {
  std::string input, output;
  DisplayCommandOptions display;
  double scale = 1;
  bool falseColour = false, legend = false, logarithmic = false, quiet = false;
  std::string quantity = "luminance", range;
};

InputLocation flag(const char *name) {
  return InputLocation{name};
}

FalseColourSettings falseColourSettings(const CLI::App &app, const TonemapOptions &o, const Image &image) {
  const char *why = "does not apply to --falsecolor, which maps luminance to colours itself";
  const ParameterValues given = o.display.toneParameters.given();
  for (const auto &[name, value] : given.all()) throw InputError(value.origin, why);
  for (const char *name : {"--tonemap", "--gamma", "--srgb", "--bits", "--gamut"})
    if (app.count(name) > 0) throw InputError(flag(name), why);
  FalseColourSettings s;
  s.legend = o.legend;
  s.logarithmic = o.logarithmic;
  s.quantity = o.quantity == "illuminance" ? FalseColourQuantity::Illuminance : FalseColourQuantity::Luminance;
  if (s.quantity == FalseColourQuantity::Illuminance && image.quantity == "radiance")
    throw InputError(flag("--quantity"),
                     fmt::format("'{}' holds radiance (W·sr⁻¹·m⁻²); illuminance in lux needs an image of irradiance "
                                 "(W·m⁻²), which a radiance image cannot give (E = πL/ρ needs the reflectance)",
                                 o.input));
  if (s.quantity == FalseColourQuantity::Luminance && image.quantity == "irradiance")
    throw InputError(flag("--quantity"),
                     fmt::format("'{}' holds irradiance (W·m⁻²): use --quantity illuminance", o.input));
  if (!o.range.empty()) {
    double minimum = 0, maximum = 0;
    char comma = 0;
    std::istringstream in(o.range);
    if (!(in >> minimum >> comma >> maximum) || comma != ',' || !(in >> std::ws).eof())
      throw InputError(flag("--range"), "expected MIN,MAX like 0,500, got '" + o.range + "'");
    s.minimum = minimum, s.maximum = maximum;
  }
  return s;
}

}  // namespace

CommandRunner addTonemapCommand(CLI::App &app) {
  auto o = std::make_shared<TonemapOptions>();
  app.add_option("image", o->input,
                 "Linear image: .exr (render's, radiance in W·sr⁻¹·m⁻²), .pfm or .hdr (Radiant's own; a Radiance "
                 "picture's values are W·sr⁻¹·m⁻² at 179 lm/W, docs/tone-mapping.md)")
      ->required();
  app.add_option("-o,--output", o->output, "Output PNG")->required();
  addDisplayOptions(app, o->display);
  app.add_option("--scale", o->scale,
                 "Multiply the image by this first (scaling every emitter of a scene scales its image so)")
      ->default_val(1.0)
      ->check(CLI::PositiveNumber);
  app.add_flag("--falsecolor", o->falseColour, "Write a false-colour map of luminance (cd/m²) instead");
  app.add_flag("--legend", o->legend, "--falsecolor: add a scale bar with labelled values");
  app.add_option("--quantity", o->quantity,
                 "--falsecolor: luminance (cd/m², of a radiance image) or illuminance (lux, of an irradiance image)")
      ->default_val("luminance")
      ->check(CLI::IsMember({"luminance", "illuminance"}));
  app.add_option("--range", o->range,
                 "--falsecolor: the scale's ends MIN,MAX in cd/m² or lux (default from the image)");
  app.add_flag("--log", o->logarithmic, "--falsecolor: logarithmic scale (default: three decades below the top)");
  app.add_flag("-q,--quiet", o->quiet, "No summary or warnings on stderr");

  return [o, &app]() {
    if (std::filesystem::path(o->output).extension() != ".png")
      throw InputError(flag("--output"), "'" + o->output + "': expected a .png file");
    if (!o->falseColour)
      for (const char *name : {"--legend", "--quantity", "--range", "--log"})
        if (app.count(name) > 0) throw InputError(flag(name), "needs --falsecolor");
    DisplaySettings display;
    if (!o->falseColour) display = displaySettings(app, o->display, 0.0);  // refuse bad flags before reading
    checkOutputFiles({{o->output, flag("--output")}}, {o->input});

    Image image = readImage(o->input);
    if (o->scale != 1)
      for (float &v : image.rgb) v = float(v * o->scale);
    LuminanceStatistics stats = luminanceStatistics(image);
    if (stats.nonFinitePixels && !o->quiet)
      fmt::print(stderr, "radiant: warning: {} pixels of '{}' hold NaN or Inf; {}\n", stats.nonFinitePixels, o->input,
                 o->falseColour ? "shown magenta" : "the gamut rule shows NaN as black, +Inf as full scale");

    if (o->falseColour) {
      FalseColourSettings settings = falseColourSettings(app, *o, image);
      if (settings.quantity == FalseColourQuantity::Illuminance && image.quantity.empty() && !o->quiet)
        fmt::print(stderr, "radiant: reading the pixels of '{}' as irradiance in W·m⁻²\n", o->input);
      FalseColourImage map = falseColour(image, settings);
      writePngBytes(map.rgb, map.width, map.height, o->output);
      if (!o->quiet)
        fmt::print(stderr, "radiant: false colour {} {:g} … {:g} {} ({}); wrote {}\n", o->quantity, map.minimum,
                   map.maximum, settings.quantity == FalseColourQuantity::Luminance ? "cd/m²" : "lux",
                   settings.logarithmic ? "log" : "linear", o->output);
      return 0;
    }
    DisplayMapping mapping(image, display);
    if (!o->quiet) reportDisplayMapping(mapping, true);
    mapping.writePng(image, o->output);
    if (!o->quiet)
      fmt::print(stderr, "radiant: log-average luminance {:.4g} cd/m², maximum {:.4g} cd/m²; wrote {}\n",
                 stats.logAverage, stats.maximum, o->output);
    return 0;
  };
}

}  // namespace radiant
