// libFuzzer target: glTF 2.0 files (docs/scene-format.md#gltf-scenes).
//
// Feeds: the input written as model.gltf, or model.glb when it starts with the GLB signature (the folder also holds
// buffer.bin and textures/ for external URIs). Entry point: loadScene. See fuzz/fuzz_inputs.h.
#include "fuzz_inputs.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static const radiant::fuzz::ScratchFolder folder("fuzz-gltf");
  try {
    radiant::fuzz::feedGltf({data, size}, folder.path());
  } catch (const radiant::InputError &) {
    // A clean refusal. Anything else escapes and libFuzzer reports it.
  }
  return 0;
}
