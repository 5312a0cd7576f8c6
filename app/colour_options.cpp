#include "colour_options.h"

#include "scene/spectral_scene.h"
#include "util/error.h"

namespace radiant {

void addColourOptions(CLI::App &app, ColourCommandOptions &o) {
  app.add_option("--colour", o.colour,
                 "Spectral scenes: run at the scene's wavelengths (spectral, ⌈N/3⌉ passes) or at the spectra's sRGB "
                 "colours (rgb, one pass; interreflected colour approximated)")
      ->default_val("spectral")
      ->check(CLI::IsMember({"spectral", "rgb"}));
  app.add_option("--white-balance", o.whiteBalance,
                 "Spectral scenes: show an equal-energy white as it is (none, slightly pink in sRGB) or as the "
                 "display's white (equal-energy, Bradford adaptation to D65)")
      ->default_val("none")
      ->check(CLI::IsMember({"none", "equal-energy"}));
}

WhiteBalance applyColourOptions(const CLI::App &app, const ColourCommandOptions &o, Scene &scene) {
  if (!scene.spectral.enabled())
    for (const char *name : {"--colour", "--white-balance"})
      if (app.count(name) > 0)
        throw InputError(InputLocation{name}, "'" + scene.sourceFile +
                                                  "' is an RGB scene; this applies to spectral scenes only "
                                                  "(docs/spectral.md)");
  WhiteBalance balance = o.whiteBalance == "equal-energy" ? WhiteBalance::EqualEnergy : WhiteBalance::None;
  if (o.colour == "rgb") convertToRgbScene(scene, balance);
  return balance;
}

}  // namespace radiant
