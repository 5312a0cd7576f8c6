#include "scene/light.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace radiant {

namespace {

/// A direction uniform in the cone of directions within acos(cosMax) of +z.
Vec3 sampleUniformCone(double u1, double u2, double cosMax) {
  const double cosTheta = 1.0 - u1 * (1.0 - cosMax);
  const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
  const double phi = 2.0 * kPi * u2;
  return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

}  // namespace

double PointLight::candelaTowards(const Vec3 &direction) const {
  switch (kind) {
    case PointLightKind::Point:
      return candela;
    case PointLightKind::Spot: {
      const double c = dot(direction, axis);
      if (c >= cosInner) return candela;
      if (c <= cosOuter) return 0.0;
      // smoothstep in cos θ between the cones: the falloff of most renderers' spots.
      const double t = (c - cosOuter) / (cosInner - cosOuter);
      return candela * t * t * (3.0 - 2.0 * t);
    }
    case PointLightKind::Photometric: {
      if (!photometry) return 0.0;
      return multiplier * photometry->candela(toLocal(direction));
    }
  }
  return 0.0;
}

double PointLight::lumens() const {
  switch (kind) {
    case PointLightKind::Point:
      return 4.0 * kPi * candela;
    case PointLightKind::Spot:
      // 2π ∫ I(μ) dμ over μ = cos θ: 1 within the inner cone, and the
      // smoothstep, whose mean over its interval is ½, between the cones.
      return 2.0 * kPi * candela * ((1.0 - cosInner) + 0.5 * (cosInner - cosOuter));
    case PointLightKind::Photometric:
      return photometry ? multiplier * photometry->lumens() : 0.0;
  }
  return 0.0;
}

Vec3 PointLight::sampleDirection(double u1, double u2, double &pdf) const {
  switch (kind) {
    case PointLightKind::Point:
      pdf = 1.0 / (4.0 * kPi);
      return toWorld(sampleUniformCone(u1, u2, -1.0));
    case PointLightKind::Spot:
      pdf = 1.0 / (2.0 * kPi * (1.0 - cosOuter));
      return toWorld(sampleUniformCone(u1, u2, cosOuter));
    case PointLightKind::Photometric:
      if (photometry) return toWorld(photometry->sample(u1, u2, pdf));
      break;
  }
  pdf = 0;
  return axis;
}

double PointLight::directionPdf(const Vec3 &direction) const {
  switch (kind) {
    case PointLightKind::Point:
      return 1.0 / (4.0 * kPi);
    case PointLightKind::Spot:
      return dot(direction, axis) > cosOuter ? 1.0 / (2.0 * kPi * (1.0 - cosOuter)) : 0.0;
    case PointLightKind::Photometric:
      return photometry ? photometry->pdf(toLocal(direction)) : 0.0;
  }
  return 0.0;
}

namespace {

/// (s, t) in [−1, 1]² to the opening: the rectangle, or the disc by the
/// concentric map (Shirley & Chiu 1997), which keeps strata compact.
Vec3 openingPoint(const PointLight &light, double s, double t) {
  if (!light.round) return light.position + light.c0 * (s * light.halfLength) + light.c90 * (t * light.halfWidth);
  if (s == 0 && t == 0) return light.position;
  double r, phi;
  if (std::abs(s) > std::abs(t)) {
    r = s, phi = kPi / 4 * (t / s);
  } else {
    r = t, phi = kPi / 2 - kPi / 4 * (s / t);
  }
  r *= light.halfLength;
  return light.position + light.c0 * (r * std::cos(phi)) + light.c90 * (r * std::sin(phi));
}

}  // namespace

Vec3 PointLight::latticePoint(int k) const {
  if (!isArea()) return position;
  const int i = k % lattice, j = k / lattice;
  return openingPoint(*this, -1 + (2 * i + 1.0) / lattice, -1 + (2 * j + 1.0) / lattice);
}

Vec3 PointLight::randomPoint(double u1, double u2) const {
  if (!isArea()) return position;
  return openingPoint(*this, 2 * u1 - 1, 2 * u2 - 1);
}

double maxCandela(const PointLight &light) {
  if (light.kind != PointLightKind::Photometric) return light.candela;
  return light.photometry ? light.multiplier * light.photometry->maxCandela() : 0.0;
}

std::string describeLight(const PointLight &light) {
  std::string text = fmt::format("'{}': {:.5g} lm, at most {:.5g} cd", light.name, light.lumens(), maxCandela(light));
  if (light.isArea())
    text += light.round ? fmt::format(", a disc of {:.4g} m", 2 * light.halfLength)
                        : fmt::format(", {:.4g} m × {:.4g} m", 2 * light.halfLength, 2 * light.halfWidth);
  if (light.photometry) {
    text += " (" + std::filesystem::path(light.photometry->file()).filename().string();
    if (!light.photometry->description().empty()) text += ": " + light.photometry->description();
    text += ")";
  }
  return text;
}

void setLightFrame(PointLight &light, const Vec3 &aim, double rotationDegrees) {
  light.axis = normalize(aim);
  // The scene's +x across the aim, unless the aim is (nearly) along x.
  const Vec3 reference = std::abs(light.axis.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 0, 1};
  Vec3 c0 = normalize(reference - light.axis * dot(reference, light.axis));
  const Vec3 c90 = cross(c0, light.axis);
  const double t = rotationDegrees * kPi / 180.0;
  light.c0 = normalize(c0 * std::cos(t) + c90 * std::sin(t));
  light.c90 = normalize(cross(light.c0, light.axis));
}

}  // namespace radiant
