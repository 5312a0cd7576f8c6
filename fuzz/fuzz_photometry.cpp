// libFuzzer target: photometric files (docs/luminaires.md#photometric-files).
//
// Feeds: the input written as lamp.ies and as lamp.ldt (the folder also holds
// tilt.tlt, so that TILT=tilt.tlt reaches the tilt-file reader). Entry points:
// readPhotometricFile on both, then what a renderer asks of an accepted
// distribution: candela, pdf and sample over a few directions, lumens,
// tiltFactor; a value out of range throws std::logic_error, which escapes.
// See fuzz/fuzz_inputs.h.
#include "fuzz_inputs.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static const radiant::fuzz::ScratchFolder folder("fuzz-photometry");
  try {
    radiant::fuzz::feedPhotometry({data, size}, folder.path());
  } catch (const radiant::InputError &) {
    // A clean refusal. Anything else escapes and libFuzzer reports it.
  }
  return 0;
}
