// libFuzzer target: MGF files (docs/scene-format.md#mgf-scenes).
//
// Feeds: the input written as scene.mgf (the folder also holds part.mgf to include and isotropic.ies for the ies
// entity). Entry point: loadScene. See fuzz/fuzz_inputs.h.
#include "fuzz_inputs.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static const radiant::fuzz::ScratchFolder folder("fuzz-mgf");
  try {
    radiant::fuzz::feedMgf({data, size}, folder.path());
  } catch (const radiant::InputError &) {
    // A clean refusal. Anything else escapes and libFuzzer reports it.
  }
  return 0;
}
