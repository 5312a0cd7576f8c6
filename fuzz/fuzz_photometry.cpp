// libFuzzer target: photometric files (docs/luminaires.md#photometric-files).
//
// Feeds: the input written as lamp.ies and as lamp.ldt (the folder also holds
// tilt.tlt, so that TILT=tilt.tlt reaches the tilt-file reader). Entry points:
// readPhotometricFile on both, then what a renderer asks of an accepted
// distribution: candela, pdf and sample over a few directions, tiltFactor.
// Self-contained (not in fuzz_inputs.cpp's table): tools/fuzz.sh and the
// regression test do not run it yet.
#include <fstream>

#include "fuzz_inputs.h"
#include "scene/photometry.h"
#include "util/error.h"

namespace {

void exercise(const radiant::PhotometricDistribution &d) {
  const radiant::Vec3 directions[] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}, {0.3, -0.4, 0.866}};
  volatile double sink = d.lumens() + d.maxCandela() + d.tiltFactor(30);
  for (const radiant::Vec3 &w : directions) sink = sink + d.candela(w) + d.pdf(w);
  for (double u : {0.0, 0.25, 0.5, 0.999999}) {
    double pdf;
    radiant::Vec3 w = d.sample(u, 1 - u, pdf);
    sink = sink + w.x + pdf + d.candela(w);
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
