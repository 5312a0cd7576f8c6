// libFuzzer target: linear images read by `radiant compare` and `tonemap`.
//
// Feeds: the input as image.exr when it starts with the OpenEXR signature,
// else as image.pfm. Entry point: readImage (src/io/image.cpp: readExr,
// readPfm). See fuzz/fuzz_inputs.h, docs/fuzzing.md.
#include "fuzz_inputs.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static const radiant::fuzz::ScratchFolder folder("fuzz-image");
  try {
    radiant::fuzz::feedImage({data, size}, folder.path());
  } catch (const radiant::InputError &) {
    // A clean refusal. Anything else escapes and libFuzzer reports it.
  }
  return 0;
}
