// Lights at a point: point, spot and photometric luminaires (docs/luminaires.md).
//
// Area emitters are materials (Material::emission, a Lambertian radiance);
// these are the other kind of source lighting designers work with: a source
// small beside the distances it lights, given by its luminous intensity
// I_v(ω) in candela. Its radiant intensity, W·sr⁻¹ per band, is
//
//   I(ω) = I_v(ω) · k,   k = colour / (683 lm/W · Y(colour))
//
// with Y the Rec.709 luminance row (docs/spectral.md: a spectral scene's
// light has a spectrum, and Y is its luminance weight over the scene's
// wavelengths): the colour's luminous efficacy turns candela into watts, so
// the light's photometry is what the file says whatever its colour. A point
// x at distance d, seen at angle θ from its normal, receives the irradiance
// E = I(ω) cos θ / d² (the inverse-square law), and nothing at all if
// anything lies between (hard shadows).
#pragma once

#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "colour/spectrum.h"
#include "scene/photometry.h"
#include "util/error.h"
#include "util/math.h"
#include "util/spectrum.h"

namespace radiant {

enum class PointLightKind {
  Point,        ///< the same intensity every way
  Spot,         ///< full intensity within an inner cone, none beyond an outer one, smooth between
  Photometric,  ///< a luminaire's measured distribution (IES, EULUMDAT)
};

struct PointLight {
  std::string name;
  InputLocation definedAt;  ///< its JSON path, for messages
  PointLightKind kind = PointLightKind::Point;
  Vec3 position;  ///< metres
  /// The light's frame: `axis` (z) is where it aims (a spot's centre, a
  /// luminaire's photometric axis), `c0` (x) its C = 0 half-plane and `c90`
  /// (y) the C = 90° one (photometry.h), all unit.
  Vec3 axis{0, -1, 0}, c0{1, 0, 0}, c90{0, 0, -1};
  /// Point and spot: the intensity on the axis, cd (multiplier applied).
  double candela = 0;
  /// Spot: cosines of the half-angles of the inner (full intensity) and
  /// outer (no light) cones; between them smoothstep in cos θ.
  double cosInner = -1, cosOuter = -1;
  std::shared_ptr<const PhotometricDistribution> photometry;  ///< Photometric
  double multiplier = 1;  ///< Photometric: times the file's candela, tilt factor included
  /// k above: radiant intensity per candela in each band, W·sr⁻¹·cd⁻¹. In a
  /// spectral scene, the spectrum at the pass's wavelengths (applySpectralPass).
  Bands wattsPerCandela{1.0 / kLuminousEfficacy};
  /// Spectral scenes: the light's spectral shape (relative), scaled by the
  /// loader so that its luminance weight over the scene's wavelengths is 1/683.
  std::optional<SampledSpectrum> spectrum;

  /// A luminaire on an area (the JSON "size" or "diameter"): its light leaves
  /// a flat luminous opening across the aim, centred on `position`, instead
  /// of one point — a rectangle of half-sides `halfLength` along c0 and
  /// `halfWidth` along c90, or a disc of radius `halfLength` when `round`.
  /// Every point of it emits I(ω)/A per unit area in the same distribution
  /// (the far-field photometry spread evenly over the opening), so nearby
  /// surfaces see its extent: soft shadow edges, no inverse-square peak
  /// beneath it. 0: a point.
  double halfLength = 0, halfWidth = 0;
  bool round = false;
  /// The deterministic rule the exact direct light integrates the opening
  /// with: `lattice` × `lattice` points (cell centres; polar cells on a disc).
  int lattice = 1;

  bool isArea() const { return halfLength > 0; }
  /// Points of the deterministic rule, each standing for 1/count of the light.
  int latticePointCount() const { return isArea() ? lattice * lattice : 1; }
  Vec3 latticePoint(int k) const;
  /// A point of the opening drawn uniformly by area from (u1, u2); `position` for a point light.
  Vec3 randomPoint(double u1, double u2) const;

  /// The light's frame's coordinates of a world direction (unit).
  Vec3 toLocal(const Vec3 &world) const { return {dot(world, c0), dot(world, c90), dot(world, axis)}; }
  Vec3 toWorld(const Vec3 &local) const { return c0 * local.x + c90 * local.y + axis * local.z; }
  /// Luminous intensity towards the unit world direction `direction`, cd.
  double candelaTowards(const Vec3 &direction) const;
  /// Radiant intensity towards it, W·sr⁻¹ per band.
  Bands intensity(const Vec3 &direction) const { return wattsPerCandela * candelaTowards(direction); }
  /// Luminous flux ∫ I_v dω, lm.
  double lumens() const;
  /// Radiant flux, W per band: wattsPerCandela × lumens (the colour does not vary with direction).
  Bands power() const { return wattsPerCandela * lumens(); }
  /// A direction (world, unit) drawn with density `pdf` per steradian,
  /// roughly following the intensity; every direction that receives light can be drawn.
  Vec3 sampleDirection(double u1, double u2, double &pdf) const;
  /// Density of sampleDirection at a world direction, per steradian.
  double directionPdf(const Vec3 &direction) const;
};

/// The irradiance at x, on a plane of unit normal n, from `light`:
/// I(ω) cos θ / d², the inverse-square law, or its mean over the lattice
/// points of a luminaire on an area, counting only the points p for which
/// `sees(p, w)` is true (w the unit direction from x to p): the shadow test,
/// exact or by ray, is the caller's.
template <typename Sees>
Bands irradianceFrom(const PointLight &light, const Vec3 &x, const Vec3 &n, const Sees &sees) {
  Bands h(0.0);
  const int count = light.latticePointCount();
  for (int k = 0; k < count; ++k) {
    const Vec3 p = light.latticePoint(k), toLight = p - x;
    const double distanceSquared = dot(toLight, toLight);
    if (!(distanceSquared > 0)) continue;
    const Vec3 w = toLight / std::sqrt(distanceSquared);
    const double cosTheta = dot(n, w);
    if (cosTheta <= 0) continue;
    const Bands intensity = light.intensity(-w);
    if (intensity.max() <= 0 || !sees(p, w)) continue;
    h += intensity * (cosTheta / (distanceSquared * count));
  }
  return h;
}

/// "'desk-1': 2400 lm, at most 1270 cd (downlight.ies: LED downlight 20 W)":
/// what the light gives, for the solver's summary and the grid report.
std::string describeLight(const PointLight &light);
/// The largest intensity of a light in any direction, cd.
double maxCandela(const PointLight &light);

/// The frame of a light aimed along `aim` (any length > 0) and turned by
/// `rotationDegrees` about it: C = 0 is the projection of `reference` (the
/// scene's +x, or +z where the aim is along x) onto the plane across the aim,
/// turned by the rotation; C = 90° is c0 × aim, counter-clockwise from C = 0
/// seen from behind the light looking along its aim.
void setLightFrame(PointLight &light, const Vec3 &aim, double rotationDegrees);

}  // namespace radiant
