// Scattering at a surface point for the per-pixel renderers and the path tracer.
//
// Directions are unit vectors in world space pointing away from the surface
// (wo towards the viewer, wi towards the light). Values are BSDF f(wo, wi) in
// sr⁻¹ per band; sampling returns the weight f·|cos θi| / pdf.
#pragma once

#include "scene/material.h"
#include "util/math.h"
#include "util/spectrum.h"

namespace radiant {

struct BsdfSample {
  Vec3 wi;
  Bands weight;    ///< f·|cos θi| / pdf (for delta lobes: the lobe's reflectance or transmittance)
  double pdf = 0;  ///< solid-angle density; meaningless for delta lobes
  bool isDelta = false;
  bool isTransmission = false;  ///< through the surface: refraction (delta) or diffuse transmission
};

class Bsdf {
 public:
  /// `shadingNormal` and `geometricNormal` as in Hit (front side); `wo` chooses which side is lit.
  /// `diffuse`, when given, replaces the material's diffuse reflectance: ρ(x) of a texture map.
  Bsdf(const Material &material, const Vec3 &shadingNormal, const Vec3 &geometricNormal, const Vec3 &wo,
       const Bands *diffuse = nullptr);

  /// f(wo, wi) of the non-delta lobes, sr⁻¹.
  Bands evaluate(const Vec3 &wi) const;
  /// Solid-angle density of sample() choosing wi, non-delta lobes only.
  double pdf(const Vec3 &wi) const;
  /// Draws wi; false if the sample was absorbed or fell on the wrong side.
  bool sample(double uLobe, double u1, double u2, BsdfSample &out) const;

  /// True if every lobe is a delta (mirror, smooth glass): light sampling is pointless.
  bool isDelta() const { return material_.isDelta(); }

 private:
  bool sameHemisphere(const Vec3 &wi) const;
  /// Of the non-transmitted samples, the share of the glossy lobe.
  double specularLobeProbability() const;
  /// The share of samples that go through a translucent surface (τ̄ against ρ̄ + τ̄).
  double transmissionLobeProbability() const;
  /// True when wi lies on the far side for diffuse transmission; its shading-frame direction in `wiLocal`.
  bool transmits(const Vec3 &wiWorld, Vec3 &wiLocal) const;
  /// Rough glass: f(wo, wi) and sample()'s density at wi; false where both are 0.
  bool roughDielectric(const Vec3 &wiWorld, Bands &f, double &pdf) const;
  /// η on the far side over η on the side of wo.
  double etaAcross() const { return entering_ ? material_.ior : 1.0 / material_.ior; }

  const Material &material_;
  Bands diffuse_;         ///< the Lambertian (or glossy base) reflectance at this point
  Frame frame_;           ///< shading frame, normal on the side of wo (except for glass)
  Vec3 geometricNormal_;  ///< flipped to the side of wo
  Vec3 woLocal_;
  bool entering_ = true;  ///< glass: wo on the front side (outside)
};

/// Fresnel reflectance of a smooth dielectric interface for unpolarised light.
/// `cosThetaI` > 0 on the side of the incident medium; `eta` = η_transmitted / η_incident.
double fresnelDielectric(double cosThetaI, double eta);

}  // namespace radiant
