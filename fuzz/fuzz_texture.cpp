// libFuzzer target: image textures (docs/textures.md).
//
// Feeds: the input as an image file, recognised by its signature (PNG and
// JPEG through stb_image, OpenEXR through OpenEXR). Entry point:
// Texture::load (src/texture/texture_file.cpp), then the lookups renderers
// and the solver make on the texture and its mip-map pyramid (bilinear,
// filtered, average, gradient). See fuzz/fuzz_inputs.h, docs/fuzzing.md.
#include "fuzz_inputs.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static const radiant::fuzz::ScratchFolder folder("fuzz-texture");
  try {
    radiant::fuzz::feedTexture({data, size}, folder.path());
  } catch (const radiant::InputError &) {
    // A clean refusal. Anything else escapes and libFuzzer reports it.
  }
  return 0;
}
