// libFuzzer target: JSON scene files (docs/scene-format.md).
//
// Feeds: the input as scene.json in a scratch folder that also holds small
// fixtures it may name (mesh.obj, mesh.mtl, textures/checker.png,
// textures/egg-crate.png). Entry point: loadScene (parseSceneJson: the JSON
// reader, materials, spectra, objects, appendObj for "obj" objects,
// loadTextures, validateScene). See fuzz/fuzz_inputs.h, docs/fuzzing.md.
#include "fuzz_inputs.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static const radiant::fuzz::ScratchFolder folder("fuzz-scene_json");
  try {
    radiant::fuzz::feedSceneJson({data, size}, folder.path());
  } catch (const radiant::InputError &) {
    // A clean refusal. Anything else escapes and libFuzzer reports it.
  }
  return 0;
}
