// libFuzzer target: radiosity solution files (docs/solution-format.md).
//
// Feeds: the input as solution.rad, its scene fingerprint (bytes 24…31)
// replaced by that of scenes/furnace/scene.json so that inputs get past the
// header. Entry point: readSolutionPasses (src/io/solution_file.cpp) for the
// furnace scene, then the solution read at points of every face as the
// renderers read it (src/radiosity/solution_query.h). See fuzz/fuzz_inputs.h.
#include "fuzz_inputs.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static const radiant::fuzz::ScratchFolder folder("fuzz-solution_file");
  try {
    radiant::fuzz::feedSolutionFile({data, size}, folder.path());
  } catch (const radiant::InputError &) {
    // A clean refusal. Anything else escapes and libFuzzer reports it.
  }
  return 0;
}
