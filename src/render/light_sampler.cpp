#include "render/light_sampler.h"

#include <algorithm>
#include <cmath>

#include "util/sampling.h"

namespace radiant {

LightSampler::LightSampler(const Scene &scene) : scene_(scene), pdfAreaByTriangle_(scene.triangles.size(), 0.0) {
  std::vector<double> power;
  for (uint32_t i = 0; i < scene.triangles.size(); ++i) {
    const Material &m = scene.materials[scene.triangles[i].material];
    if (!m.isEmitter()) continue;
    double area = scene.triangleArea(scene.triangles[i]);
    emitters_.push_back(i);
    power.push_back(kPi * area * m.emission.average());
    totalPower_ += m.emission * (kPi * area);
  }
  for (const PointLight &light : scene.lights) {
    const Bands flux = light.power();
    power.push_back(flux.average());
    totalPower_ += flux;
  }
  double total = 0;
  for (double p : power) total += p;
  if (!(total > 0)) return;  // nothing emits (a pass of a spectral scene outside every light's spectrum)
  cumulative_.resize(power.size());
  probability_.resize(power.size());
  double running = 0;
  for (size_t k = 0; k < power.size(); ++k) {
    probability_[k] = power[k] / total;
    running += probability_[k];
    cumulative_[k] = running;
    if (k < emitters_.size())
      pdfAreaByTriangle_[emitters_[k]] = probability_[k] / scene.triangleArea(scene.triangles[emitters_[k]]);
  }
  if (!cumulative_.empty()) cumulative_.back() = 1.0;
}

bool LightSampler::sample(double uSelect, double u1, double u2, LightSample &out) const {
  if (cumulative_.empty()) return false;
  size_t k = std::upper_bound(cumulative_.begin(), cumulative_.end(), uSelect) - cumulative_.begin();
  k = std::min(k, cumulative_.size() - 1);
  if (k >= emitters_.size()) {
    out.pointLight = &scene_.lights[k - emitters_.size()];
    out.position = out.pointLight->randomPoint(u1, u2);  // a luminaire on an area: a point of it
    out.probability = probability_[k];
    return out.probability > 0;
  }
  out.pointLight = nullptr;
  uint32_t index = emitters_[k];
  const Triangle &t = scene_.triangles[index];
  double b1, b2;
  sampleUniformTriangle(u1, u2, b1, b2);
  const Vec3 &p0 = scene_.positions[t.v[0]], &p1 = scene_.positions[t.v[1]], &p2 = scene_.positions[t.v[2]];
  out.position = p0 * (1 - b1 - b2) + p1 * b1 + p2 * b2;
  out.normal = scene_.triangleNormal(t);
  out.radiance = scene_.materials[t.material].emission;
  out.pdfArea = pdfAreaByTriangle_[index];
  out.triangle = index;
  return true;
}

namespace {

/// A point light's share: f · I(ω) · |cos θ| / (d² p(light)), from a delta
/// in position, so no other strategy finds it and its weight is 1.
Bands estimatePointLight(const PointLight &light, const Vec3 &position, double probability, const RayTracer &tracer,
                         const Hit &hit, const Bsdf &bsdf) {
  const Vec3 toLight = position - hit.position;
  const double distance2 = dot(toLight, toLight);
  if (!(distance2 > 0)) return Bands(0.0);
  const Vec3 wi = toLight / std::sqrt(distance2);
  const Bands intensity = light.intensity(-wi);
  if (intensity.max() <= 0) return Bands(0.0);
  const Bands f = bsdf.evaluate(wi);
  if (f.max() <= 0) return Bands(0.0);
  // The light has no surface: the shadow ray ends at the point, offset along −wi.
  if (!tracer.seesPoint(hit.position, hit.geometricNormal, position)) return Bands(0.0);
  const double cosSurface = std::abs(dot(wi, hit.shadingNormal));
  return f * intensity * (cosSurface / (distance2 * probability));
}

}  // namespace

Bands estimateDirectLight(const LightSampler &lights, const RayTracer &tracer, const Hit &hit, const Bsdf &bsdf,
                          Sampler &rng, LightWeighting weighting) {
  LightSample light;
  double uSelect = rng.next(), u1 = rng.next(), u2 = rng.next();
  if (!lights.sample(uSelect, u1, u2, light)) return Bands(0.0);
  if (light.pointLight)
    return estimatePointLight(*light.pointLight, light.position, light.probability, tracer, hit, bsdf);
  Vec3 toLight = light.position - hit.position;
  double distance2 = dot(toLight, toLight);
  if (distance2 <= 0) return Bands(0.0);
  Vec3 wi = toLight / std::sqrt(distance2);
  double cosLight = -dot(wi, light.normal);
  if (cosLight <= 0) return Bands(0.0);  // the emitter's back does not emit
  Bands f = bsdf.evaluate(wi);
  if (f.max() <= 0) return Bands(0.0);
  if (!tracer.visible(hit.position, hit.geometricNormal, light.position, light.normal)) return Bands(0.0);
  double cosSurface = std::abs(dot(wi, hit.shadingNormal));
  if (weighting == LightWeighting::Alone)
    return f * light.radiance * (cosSurface * cosLight / (distance2 * light.pdfArea));
  double lightPdf = light.pdfArea * distance2 / cosLight;  // per solid angle
  double weight = powerHeuristic(lightPdf, bsdf.pdf(wi));
  return f * light.radiance * (cosSurface * weight / lightPdf);
}

Bands pointLightIrradiance(const RayTracer &tracer, const Hit &hit) {
  Bands h(0.0);
  // cos θ against the shading normal; nothing from behind the geometric surface.
  for (const PointLight &light : tracer.scene().lights)
    h += irradianceFrom(light, hit.position, hit.shadingNormal, [&](const Vec3 &p, const Vec3 &w) {
      return dot(w, hit.geometricNormal) > 0 && tracer.seesPoint(hit.position, hit.geometricNormal, p);
    });
  return h;
}

double LightSampler::pdfArea(uint32_t triangle) const {
  return triangle < pdfAreaByTriangle_.size() ? pdfAreaByTriangle_[triangle] : 0.0;
}

}  // namespace radiant
