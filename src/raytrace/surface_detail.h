// What a material's maps change at a point of a surface (Cohen & Wallace §9.4,
// eq. 9.11; Chen & Wu, SIGGRAPH 1990): the diffuse reflectance ρ(x) of a
// texture map and the shading normal of a bump or normal map. The geometric
// normal, and with it visibility and emission, never changes.
#pragma once

#include <span>

#include "raytrace/ray_tracer.h"
#include "scene/scene.h"

namespace radiant {

/// A texture map's reflectance is clamped below 1: a white texel on a Kd = 1
/// material must not make the radiosity series diverge.
constexpr double kMaxTexturedReflectance = kMaxDiffuseReflectance;

/// The texture parameterisation of a triangle at barycentrics (b1, b2): the
/// material's texture coordinates (its uvScale applied) and the derivatives of
/// position along them, metres per unit of u and v.
struct SurfaceParameterisation {
  double u = 0, v = 0;
  Vec3 dpdu, dpdv;
  bool hasUv = false;     ///< false: the face has no texture coordinates (u = v = 0)
  double uvPerMetre = 0;  ///< texture-space length per metre on the surface (for filter widths)
};
SurfaceParameterisation surfaceParameterisation(const Scene &scene, const Triangle &triangle, double b1, double b2);

struct SurfaceDetail {
  Bands diffuse;       ///< ρ(x): the material's diffuse reflectance times its texture there
  Vec3 shadingNormal;  ///< the hit's, perturbed by the bump or normal map, on the geometric normal's side
};

/// The detail at a hit. `footprint` is the width on the surface, metres, that
/// one pixel covers there (the texture is filtered over it); 0 for the finest texels.
SurfaceDetail surfaceDetail(const Scene &scene, const Hit &hit, double footprint = 0);

/// ρ̄: the mean of ρ(x) over a convex polygon lying on a face (an element of
/// the radiosity mesh), integrated over the texture, not point-sampled — the
/// reflectance the radiosity solution is computed with (C&W eq. 9.11).
Bands averageDiffuse(const Scene &scene, uint32_t face, std::span<const Vec3> polygon);

}  // namespace radiant
