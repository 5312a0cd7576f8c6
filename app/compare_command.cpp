// radiant compare TEST REFERENCE — per-channel mean ratio, RMSE and relative
// MSE, and optionally a false-colour difference image.
#include <fmt/format.h>

#include <filesystem>
#include <optional>

#include "commands.h"
#include "display/emitter_mask.h"
#include "io/compare.h"
#include "io/image.h"
#include "io/output_files.h"
#include "util/error.h"

namespace radiant {

namespace {
struct CompareOptions {
  std::string test, reference, differencePath, testVariance, referenceVariance;
  double differenceRange = 0.2;
  bool json = false, withoutEmitters = false;
};
}  // namespace

CommandRunner addCompareCommand(CLI::App &app) {
  auto options = std::make_shared<CompareOptions>();
  app.add_option("test", options->test, "Image to measure (.exr or .pfm, linear)")->required();
  app.add_option("reference", options->reference, "Reference image (.exr or .pfm, linear)")->required();
  app.add_option("--diff", options->differencePath,
                 "Write a false-colour PNG of the relative luminance difference (blue: darker, red: brighter)");
  app.add_option("--diff-range", options->differenceRange, "Relative difference at which the false colour saturates")
      ->default_val(0.2)
      ->check(CLI::PositiveNumber);
  app.add_option("--test-variance", options->testVariance,
                 "Variance of each test pixel's mean (radiant render --variance): adds z-scores of the difference");
  app.add_option("--reference-variance", options->referenceVariance,
                 "Variance of each reference pixel's mean; without it the reference counts as noise-free");
  app.add_flag("--without-emitters", options->withoutEmitters,
               "Leave out the pixels that show a light and their eight neighbours (the reference's emitter channel, "
               "else the test's: EXRs written by radiant render), so that the figures are the lit surfaces'");
  app.add_flag("--json", options->json, "Print the figures as JSON");

  return [options]() {
    if (!options->differencePath.empty()) {
      if (std::filesystem::path(options->differencePath).extension() != ".png")
        throw InputError(InputLocation{"--diff"}, "'" + options->differencePath + "': expected a .png file");
      checkOutputFiles({{options->differencePath, InputLocation{"--diff"}}}, {options->test, options->reference});
    }
    Image test = readImage(options->test);
    Image reference = readImage(options->reference);
    std::vector<uint8_t> leaveOut;
    if (options->withoutEmitters) {
      const Image &covered = !reference.emitterFraction.empty() ? reference : test;
      if (covered.emitterFraction.empty())
        throw InputError(InputLocation{"--without-emitters"},
                         "neither '" + options->test + "' nor '" + options->reference +
                             "' has an emitter channel (an EXR written by radiant render has one)");
      leaveOut = emitterPixelMask(covered);
    }
    ImageComparison c = compareImages(test, reference, options->test, options->reference, leaveOut);
    const char *names[4] = {"R", "G", "B", "all"};
    std::optional<NoiseAgreement> noise;
    if (!options->testVariance.empty() || !options->referenceVariance.empty()) {
      auto load = [&](const std::string &path, const char *role) {
        if (path.empty()) return Image();
        Image v = readImage(path);
        if (v.width != test.width || v.height != test.height)
          throw InputError(InputLocation{path}, std::string(role) + " variance image size differs from the images");
        return v;
      };
      noise = noiseAgreement(test, reference, load(options->testVariance, "test"),
                             load(options->referenceVariance, "reference"));
    }
    if (options->json) {
      fmt::print("{{\"pixels\": {}, \"non_finite_pixels\": {}", c.pixels, c.nonFinitePixels);
      if (options->withoutEmitters) fmt::print(", \"left_out_pixels\": {}", c.leftOut);
      for (int i = 0; i < 4; ++i) {
        const ChannelComparison &ch = i < 3 ? c.channels[i] : c.average;
        fmt::print(
            ", \"{}\": {{\"mean_test\": {:.9g}, \"mean_reference\": {:.9g}, \"mean_ratio\": {:.9g}, "
            "\"rmse\": {:.9g}, \"relmse\": {:.9g}}}",
            names[i], ch.meanTest, ch.meanReference, ch.meanRatio, ch.rmse, ch.relativeMse);
      }
      if (noise)
        fmt::print(
            ", \"z\": [{:.4g}, {:.4g}, {:.4g}], \"blocks\": {}, \"block_rms_z\": {:.4g}, "
            "\"block_max_abs_z\": {:.4g}, \"blocks_beyond_4\": {}",
            noise->imageZ[0], noise->imageZ[1], noise->imageZ[2], noise->blocks, noise->blockRmsZ, noise->blockMaxAbsZ,
            noise->blocksBeyond4);
      fmt::print("}}\n");
    } else {
      fmt::print("{:<8}{:>14}{:>14}{:>12}{:>14}{:>14}\n", "channel", "mean test", "mean ref", "ratio", "RMSE",
                 "relMSE");
      for (int i = 0; i < 4; ++i) {
        const ChannelComparison &ch = i < 3 ? c.channels[i] : c.average;
        fmt::print("{:<8}{:>14.6g}{:>14.6g}{:>12.6f}{:>14.6g}{:>14.6g}\n", names[i], ch.meanTest, ch.meanReference,
                   ch.meanRatio, ch.rmse, ch.relativeMse);
      }
      if (noise) {
        fmt::print("difference of means in standard errors: R {:+.2f}  G {:+.2f}  B {:+.2f}\n", noise->imageZ[0],
                   noise->imageZ[1], noise->imageZ[2]);
        fmt::print(
            "16x16 blocks x channels: {}; RMS z {:.3f} (about 1 when the images agree within noise), "
            "max |z| {:.2f}, {} beyond 4\n",
            noise->blocks, noise->blockRmsZ, noise->blockMaxAbsZ, noise->blocksBeyond4);
      }
      if (c.nonFinitePixels) fmt::print("warning: {} pixels with NaN or Inf were left out\n", c.nonFinitePixels);
      if (options->withoutEmitters) fmt::print("left out: {} pixels showing a light or next to one\n", c.leftOut);
    }
    if (!options->differencePath.empty())
      writePngBytes(differenceImage(test, reference, options->differenceRange), test.width, test.height,
                    options->differencePath);
    return 0;
  };
}

}  // namespace radiant
