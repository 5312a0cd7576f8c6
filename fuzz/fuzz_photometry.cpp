// libFuzzer target: photometric files (docs/luminaires.md#photometric-files).
//
// Feeds: the input written as lamp.ies and as lamp.ldt (the folder also holds
// tilt.tlt, so that TILT=tilt.tlt reaches the tilt-file reader). Entry points:
// readPhotometricFile on both, then what a renderer asks of an accepted
// distribution: candela, pdf and sample over a few directions, tiltFactor.
// Self-contained (not in fuzz_inputs.cpp's table): tools/fuzz.sh and the
// regression test do not run it yet.
#include <cmath>
#include <fstream>

#include "fuzz_inputs.h"
#include "scene/photometry.h"
#include "util/error.h"

namespace {

/// An accepted file must give a finite, non-negative distribution: anything
/// else traps, and libFuzzer reports it.
void require(bool condition) {
  if (!condition) __builtin_trap();
}

void exercise(const radiant::PhotometricDistribution &d) {
  const radiant::Vec3 directions[] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}, {0.3, -0.4, 0.866}};
  require(std::isfinite(d.lumens()) && d.lumens() >= 0 && std::isfinite(d.maxCandela()));
  require(std::isfinite(d.tiltFactor(30)));
  for (const radiant::Vec3 &w : directions) {
    double candela = d.candela(w), pdf = d.pdf(w);
    require(std::isfinite(candela) && candela >= 0 && std::isfinite(pdf) && pdf >= 0);
    require(candela == 0 || pdf > 0);
  }
  for (double u : {0.0, 0.25, 0.5, 0.999999}) {
    double pdf;
    radiant::Vec3 w = d.sample(u, 1 - u, pdf);
    require(std::isfinite(pdf) && pdf >= 0);
    require(pdf == 0 || std::abs(radiant::length(w) - 1) < 1e-9);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static const radiant::fuzz::ScratchFolder folder("fuzz-photometry");
  static const bool tiltWritten = [] {
    std::ofstream(folder.path() + "/tilt.tlt") << "1\n3\n0 45 90\n1 0.9 0.8\n";
    return true;
  }();
  (void)tiltWritten;
  for (const char *name : {"/lamp.ies", "/lamp.ldt"}) {
    std::string path = folder.path() + name;
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char *>(data), static_cast<std::streamsize>(size));
    try {
      exercise(*radiant::readPhotometricFile(path));
    } catch (const radiant::InputError &) {
      // A clean refusal. Anything else escapes and libFuzzer reports it.
    }
  }
  return 0;
}
