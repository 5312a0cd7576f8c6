// radiant compare TEST REFERENCE — per-channel mean ratio, RMSE and relative
// MSE, and optionally a false-colour difference image.
#include <fmt/format.h>

#include "commands.h"
#include "io/compare.h"
#include "io/image.h"

namespace radiant {

namespace {
struct CompareOptions {
  std::string test, reference, differencePath;
  double differenceRange = 0.2;
  bool json = false;
};
}  // namespace

CommandRunner addCompareCommand(CLI::App &app) {
  auto options = std::make_shared<CompareOptions>();
  app.add_option("test", options->test, "Image to measure (.exr or .pfm, linear)")->required();
  app.add_option("reference", options->reference, "Reference image (.exr or .pfm, linear)")->required();
  app.add_option("--diff", options->differencePath,
                 "Write a false-colour PNG of the relative luminance difference (blue: darker, red: brighter)");
  app.add_option("--diff-range", options->differenceRange,
                 "Relative difference at which the false colour saturates")
      ->default_val(0.2)
      ->check(CLI::PositiveNumber);
  app.add_flag("--json", options->json, "Print the figures as JSON");

  return [options]() {
    Image test = readImage(options->test);
    Image reference = readImage(options->reference);
    ImageComparison c = compareImages(test, reference, options->test, options->reference);
    const char *names[4] = {"R", "G", "B", "all"};
    if (options->json) {
      fmt::print("{{\"pixels\": {}, \"non_finite_pixels\": {}", c.pixels, c.nonFinitePixels);
      for (int i = 0; i < 4; ++i) {
        const ChannelComparison &ch = i < 3 ? c.channels[i] : c.average;
        fmt::print(", \"{}\": {{\"mean_test\": {:.9g}, \"mean_reference\": {:.9g}, \"mean_ratio\": {:.9g}, "
                   "\"rmse\": {:.9g}, \"relmse\": {:.9g}}}",
                   names[i], ch.meanTest, ch.meanReference, ch.meanRatio, ch.rmse, ch.relativeMse);
      }
      fmt::print("}}\n");
    } else {
      fmt::print("{:<8}{:>14}{:>14}{:>12}{:>14}{:>14}\n", "channel", "mean test", "mean ref", "ratio", "RMSE",
                 "relMSE");
      for (int i = 0; i < 4; ++i) {
        const ChannelComparison &ch = i < 3 ? c.channels[i] : c.average;
        fmt::print("{:<8}{:>14.6g}{:>14.6g}{:>12.6f}{:>14.6g}{:>14.6g}\n", names[i], ch.meanTest, ch.meanReference,
                   ch.meanRatio, ch.rmse, ch.relativeMse);
      }
      if (c.nonFinitePixels)
        fmt::print("warning: {} pixels with NaN or Inf were left out\n", c.nonFinitePixels);
    }
    if (!options->differencePath.empty())
      writePngBytes(differenceImage(test, reference, options->differenceRange), test.width, test.height,
                    options->differencePath);
    return 0;
  };
}

}  // namespace radiant
