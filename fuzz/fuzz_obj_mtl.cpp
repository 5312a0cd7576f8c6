// libFuzzer target: Wavefront OBJ and MTL files (a bare OBJ scene).
//
// Feeds: the input split at the line "#--- model.mtl ---" into model.obj and
// model.mtl (the OBJ reads the MTL through "mtllib model.mtl"; the folder also
// holds textures/checker.png and textures/egg-crate.png for map_Kd and bump).
// Entry point: loadScene on model.obj (appendObj: the line scan, tinyobjloader,
// the MTL conversion, loadTextures, validateScene). See fuzz/fuzz_inputs.h.
#include "fuzz_inputs.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static const radiant::fuzz::ScratchFolder folder("fuzz-obj_mtl");
  try {
    radiant::fuzz::feedObjMtl({data, size}, folder.path());
  } catch (const radiant::InputError &) {
    // A clean refusal. Anything else escapes and libFuzzer reports it.
  }
  return 0;
}
