// libFuzzer target: Radiance RGBE images (.hdr).
//
// Feeds: the input written as image.hdr. Entry point: readImage (what radiant tonemap and compare read).
// See fuzz/fuzz_inputs.h.
#include "fuzz_inputs.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static const radiant::fuzz::ScratchFolder folder("fuzz-hdr");
  try {
    radiant::fuzz::feedHdr({data, size}, folder.path());
  } catch (const radiant::InputError &) {
    // A clean refusal. Anything else escapes and libFuzzer reports it.
  }
  return 0;
}
