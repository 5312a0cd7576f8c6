// Surface materials, in SI radiometry.
//
// A material is one of four scattering models plus optional emission. The
// radiosity stages see only the diffuse part (reflectance ρ per band); the
// per-pixel renderers and the path tracer see the whole model.
#pragma once

#include <optional>
#include <string>

#include "colour/spectrum.h"
#include "texture/texture.h"
#include "util/error.h"
#include "util/spectrum.h"

namespace radiant {

enum class MaterialKind {
  Lambertian,  ///< ideal diffuse, reflectance `diffuse` (ρ, dimensionless, per band)
  Mirror,      ///< ideal specular reflection with reflectance `specular`
  Dielectric,  ///< glass: Fresnel reflection and refraction, index `ior`, transmittance `specular`;
               ///< smooth, or rough with `transmissionRoughness` > 0 (GGX microfacets, Walter et al. 2007)
  Glossy,      ///< `diffuse` Lambertian base plus a GGX microfacet lobe of reflectance `specular`, `roughness`
};

const char *materialKindName(MaterialKind kind);

/// The largest diffuse reflectance Radiant uses: ρ ≥ 1 makes radiosity's
/// Neumann series diverge (C&W §5.2), so a white texel, or an MTL's Kd = 1
/// without a texture, is taken down to this.
constexpr double kMaxDiffuseReflectance = 0.999;

/// The values of a spectral scene's material given as spectra (docs/spectral.md).
/// A value without a spectrum is grey: the same at every wavelength.
struct MaterialSpectra {
  std::optional<SampledSpectrum> diffuse, specular, emission, transmittance;
  bool any() const { return diffuse || specular || emission || transmittance; }
};

struct Material {
  std::string name;
  MaterialKind kind = MaterialKind::Lambertian;
  Bands diffuse{0.5};      ///< Lambertian reflectance ρ in [0,1)
  Bands specular{0.0};     ///< mirror / glossy reflectance or glass transmittance filter
  double ior = 1.5;        ///< index of refraction (Dielectric)
  double roughness = 0.2;  ///< GGX α (Glossy), in (0, 1]
  /// GGX α of a Dielectric's microfacets, in (0, 1]; 0: smooth glass (the
  /// default). Not `roughness`, whose default would make every glass rough.
  double transmissionRoughness = 0;
  /// Emitted radiance, W·sr⁻¹·m⁻², uniform over the front hemisphere only.
  Bands emission{0.0};
  /// Both sides of each face reflect (and emit) alike (MGF `sides 2`, JSON
  /// "two_sided"): the radiosity mesh gets a patch on each side.
  bool twoSided = false;
  /// Diffuse transmittance τ per band (MGF `td`, JSON "diffuse_transmittance";
  /// Lambertian and glossy only): of the light arriving on one side, τ leaves
  /// the other side diffusely, BTDF τ/π. The τ of the side the light leaves
  /// from applies. τ > 0 makes the material two-sided; ρ + τ < 1.
  Bands transmittance{0.0};
  bool isTranslucent() const { return transmittance.max() > 0; }

  /// Spectral scenes only. The Bands above then hold the values at the three
  /// wavelengths of the current pass (applySpectralPass), or, outside a pass,
  /// the spectra's linear sRGB colour.
  MaterialSpectra spectra;

  // Surface detail (docs/textures.md; C&W §9.4). Paths are resolved against
  // the file that named them; the loader loads each image once into
  // Scene::textures and sets the indices (−1: none).
  std::string diffuseTexture;  ///< map_Kd / "texture": multiplies `diffuse`
  std::string bumpTexture;     ///< bump / map_Bump / "bump": a height map
  std::string normalTexture;   ///< "normal_map": tangent-space normals (JSON only)
  double bumpScale = 1.0;      ///< -bm / "bump_scale": height per unit of map value, scene units
  int diffuseTextureIndex = -1, bumpTextureIndex = -1, normalTextureIndex = -1;
  TextureWrap textureWrap = TextureWrap::Repeat;  ///< -clamp on / "texture_wrap"
  double uvScale[2] = {1, 1};  ///< -s u v / "texture_scale": texture coordinates are multiplied by it
  /// Where the maps were named (MTL file and line, or JSON path), for messages.
  InputLocation diffuseTextureFrom, bumpTextureFrom, normalTextureFrom;
  /// Where the material was defined (its JSON path, or the MTL file and its
  /// newmtl line): checks made after loading name it there.
  InputLocation definedAt;

  bool isEmitter() const { return emission.max() > 0.0; }
  bool hasSurfaceDetail() const { return diffuseTextureIndex >= 0 || bumpTextureIndex >= 0 || normalTextureIndex >= 0; }
  /// Glass with microfacets. An index of 1 (MGF's thin sheet) bends no ray
  /// whatever the facets' slopes: that glass stays smooth (pbrt-v4 does the same).
  bool isRoughDielectric() const { return kind == MaterialKind::Dielectric && transmissionRoughness > 0 && ior != 1; }
  /// True when the surface scatters only into a finite set of directions.
  bool isDelta() const {
    return kind == MaterialKind::Mirror || (kind == MaterialKind::Dielectric && !isRoughDielectric());
  }
  /// Mirrors and glass, smooth or rough: surfaces the radiosity solution
  /// holds no light for (their ρ is 0), which the renderers that read it
  /// look past rather than shade (two-pass visible points, the irradiance meter).
  bool isSpecular() const { return kind == MaterialKind::Mirror || kind == MaterialKind::Dielectric; }
};

}  // namespace radiant
