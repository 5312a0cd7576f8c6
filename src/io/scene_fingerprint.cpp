// The scene fingerprint of a solution file (docs/solution-format.md#the-scene-fingerprint):
// what the solution depends on, hashed, so that a solution is refused for another scene.
#include <cmath>

#include "io/solution_file.h"

namespace radiant {

namespace {

/// FNV-1a, 64 bit.
struct Fingerprint {
  uint64_t h = 0xcbf29ce484222325ULL;
  void bytes(const void *data, size_t n) {
    auto *p = static_cast<const unsigned char *>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ULL;
  }
  template <typename T>
  void value(const T &v) {
    bytes(&v, sizeof v);
  }
};

}  // namespace

uint64_t sceneFingerprint(const Scene &scene) {
  Fingerprint f;
  f.value(uint64_t(scene.positions.size()));
  for (const Vec3 &p : scene.positions) f.value(p.x), f.value(p.y), f.value(p.z);
  f.value(uint64_t(scene.faces.size()));
  for (const Face &face : scene.faces) {
    f.value(face.vertexCount);
    for (int k = 0; k < face.vertexCount; ++k) f.value(face.vertices[k]);
    f.value(face.material);
  }
  f.value(uint64_t(scene.materials.size()));
  // A spectral scene's bands change from pass to pass: its spectra identify it.
  const bool spectral = scene.spectral.enabled();
  f.value(uint64_t(scene.spectral.wavelengths.size()));
  for (double nm : scene.spectral.wavelengths) f.value(nm);
  // Tagged and counted, so that no two different material lists hash the same sequence.
  auto spectrum = [&](const std::optional<SampledSpectrum> &s, const Bands &grey) {
    f.value(uint8_t(s ? 1 : 0));
    if (!s) return f.value(grey[0]);
    f.value(uint64_t(s->values.size()));
    for (size_t i = 0; i < s->values.size(); ++i) f.value(s->wavelengths[i]), f.value(s->values[i]);
  };
  for (const Material &m : scene.materials) {
    f.value(int(m.kind));
    // A texture changes ρ̄ (and so the solution): its texels, wrap and scale, and
    // (below) the texture coordinates, identify it.
    if (m.diffuseTextureIndex >= 0) {
      const Texture &texture = scene.textures[m.diffuseTextureIndex];
      f.value(uint8_t(2)), f.value(texture.width()), f.value(texture.height()), f.value(int(texture.wrap()));
      const std::span<const float> texels = texture.finestTexels();
      f.bytes(texels.data(), texels.size_bytes());
      f.value(m.uvScale[0]), f.value(m.uvScale[1]);
    }
    // Translucency (a scene from before it existed: nothing added).
    if (m.isTranslucent() || m.spectra.transmittance) {
      f.value(uint8_t(3));
      if (spectral)
        spectrum(m.spectra.transmittance, m.transmittance);
      else
        for (int b = 0; b < kBandCount; ++b) f.value(m.transmittance[b]);
    }
    // Rough glass, like the glass's transmittance below (smooth glass: nothing added, old fingerprints hold).
    if (m.transmissionRoughness > 0) f.value(uint8_t(4)), f.value(m.transmissionRoughness);
    if (spectral) {
      spectrum(m.spectra.diffuse, m.diffuse), spectrum(m.spectra.emission, m.emission);
      spectrum(m.spectra.specular, m.specular);
      continue;
    }
    for (int b = 0; b < kBandCount; ++b) f.value(m.diffuse[b]), f.value(m.emission[b]), f.value(m.specular[b]);
  }
  // Point lights (none: the fingerprint of a scene from before they existed).
  if (!scene.lights.empty()) f.value(uint64_t(scene.lights.size()));
  for (const PointLight &light : scene.lights) {
    f.value(int(light.kind));
    for (const Vec3 *v : {&light.position, &light.axis, &light.c0}) f.value(v->x), f.value(v->y), f.value(v->z);
    f.value(light.candela), f.value(light.cosInner), f.value(light.cosOuter), f.value(light.multiplier);
    f.value(light.halfLength), f.value(light.halfWidth), f.value(uint8_t(light.round)), f.value(light.lattice);
    if (spectral)
      spectrum(light.spectrum, light.wattsPerCandela);
    else
      for (int b = 0; b < kBandCount; ++b) f.value(light.wattsPerCandela[b]);
    // A photometric web by its flux and its intensity on a fixed set of directions.
    if (light.photometry) {
      f.value(light.photometry->lumens());
      for (int i = 0; i < 64; ++i) {
        const double z = 1 - (i + 0.5) / 32, r = std::sqrt(std::max(0.0, 1 - z * z)), phi = 2.399963229728653 * i;
        f.value(light.photometry->candela(Vec3{r * std::cos(phi), r * std::sin(phi), z}));
      }
    }
  }
  // Texture coordinates of textured faces (they decide each element's ρ̄).
  for (const Face &face : scene.faces)
    if (scene.materials[face.material].diffuseTextureIndex >= 0)
      for (int k = 0; k < face.vertexCount; ++k) {
        f.value(face.uvs[k]);
        if (face.uvs[k] >= 0)
          f.value(scene.uvs[2 * size_t(face.uvs[k])]), f.value(scene.uvs[2 * size_t(face.uvs[k]) + 1]);
      }
  return f.h;
}

}  // namespace radiant
