// Loading the images a scene's materials name (docs/textures.md): each file
// once, with the encoding its use needs, after the scene is parsed.

#include <fmt/format.h>

#include <map>
#include <tuple>

#include "scene/load_detail.h"

namespace radiant {

void detail::loadTextures(Scene &scene) {
  std::map<std::tuple<std::string, TextureEncoding, TextureWrap>, int> loaded;
  auto load = [&](const std::string &path, TextureEncoding encoding, TextureWrap wrap, const InputLocation &from,
                  const char *what) -> int {
    if (path.empty()) return -1;
    auto key = std::make_tuple(path, encoding, wrap);
    if (auto it = loaded.find(key); it != loaded.end()) return it->second;
    try {
      scene.textures.push_back(Texture::load(path, encoding, wrap));
    } catch (const InputError &e) {
      // Name the line or JSON path that named the file, then what is wrong with it.
      throw InputError(from.file.empty() ? e.location() : from, fmt::format("{} {}", what, e.what()));
    }
    return loaded[key] = int(scene.textures.size()) - 1;
  };
  for (Material &m : scene.materials) {
    if (scene.spectral.enabled() && (!m.diffuseTexture.empty()))
      throw InputError(m.diffuseTextureFrom, "material '" + m.name +
                                                 "': a texture is an sRGB image, and this scene is spectral: "
                                                 "spectral textures are not supported (docs/spectral.md)");
    // An image embedded in a glTF file was decoded by its loader already (diffuseTexture names it for messages).
    if (m.diffuseTextureIndex < 0)
      m.diffuseTextureIndex =
          load(m.diffuseTexture, TextureEncoding::Colour, m.textureWrap, m.diffuseTextureFrom, "texture");
    m.bumpTextureIndex = load(m.bumpTexture, TextureEncoding::Data, m.textureWrap, m.bumpTextureFrom, "bump map");
    m.normalTextureIndex =
        load(m.normalTexture, TextureEncoding::Data, m.textureWrap, m.normalTextureFrom, "normal map");
  }
  // A map on a face without texture coordinates shows one texel everywhere: say so.
  std::vector<bool> warned(scene.objects.size());
  for (const Face &f : scene.faces) {
    const Material &m = scene.materials[f.material];
    if (!m.hasSurfaceDetail() || f.uvs[0] >= 0 || f.object >= warned.size() || warned[f.object]) continue;
    warned[f.object] = true;
    scene.warnings.push_back(
        fmt::format("object '{}' has no texture coordinates, so the maps of its material '{}' "
                    "show their value at (0, 0) everywhere",
                    scene.objects[f.object].name, m.name));
  }
}

}  // namespace radiant
