#include "render/two_pass.h"

#include "raytrace/surface_detail.h"
#include "render/bsdf.h"
#include "util/error.h"

namespace radiant {

bool findVisiblePoint(const RayTracer &tracer, const Solution &solution, Ray ray, Sampler &rng, VisiblePoint &out,
                      double pixelSpread, Reconstruction reconstruction) {
  constexpr int kMaxSpecularBounces = 64;
  const Scene &scene = tracer.scene();
  out.throughput = Bands(1.0);
  double travelled = 0;  // along the specular chain: the pixel's footprint grows with it
  for (int bounce = 0; bounce < kMaxSpecularBounces; ++bounce) {
    out.specularBounces = bounce;
    if (!tracer.intersect(ray, out.hit)) return false;
    travelled += out.hit.distance;
    const Material &material = scene.materials[out.hit.material];
    out.wo = -ray.direction;
    // Rough glass too: the solution holds nothing for it, so the view goes
    // through (or off) it by a sampled direction, weighted f·cos/pdf.
    if (material.isSpecular()) {
      Bsdf bsdf(material, out.hit.shadingNormal, out.hit.geometricNormal, out.wo);
      BsdfSample s;
      double uLobe = rng.next(), u1 = rng.next(), u2 = rng.next();
      if (!bsdf.sample(uLobe, u1, u2, s)) return false;
      out.throughput *= s.weight;
      ray = tracer.spawnRay(out.hit.position, out.hit.geometricNormal, s.wi);
      continue;
    }
    if (!locateHit(solution, out.hit, out.wo, out.at, reconstruction)) return false;
    out.material = &material;
    out.reflectance = material.diffuse;
    out.unbumpedNormal = out.hit.shadingNormal;
    if (material.hasSurfaceDetail()) {
      const SurfaceDetail detail = surfaceDetail(scene, out.hit, travelled * pixelSpread);
      out.reflectance = detail.diffuse;
      out.hit.shadingNormal = detail.shadingNormal;
      applySurfaceDetail(solution, material, detail.diffuse, out.at);
    }
    return true;
  }
  return false;
}

const Solution &requireSolution(const RenderContext &context) {
  if (!context.solution)
    throw InputError(InputLocation::ofParameter("method"), "this method needs a radiosity solution");
  return *context.solution;
}

const ParameterTable &selectiveParameters() {
  static const ParameterTable table = {
      {"selective", ParameterType::Flag, "false",
       "re-evaluate per pixel only where the solution is flagged inaccurate (C&W §9.3.3)"},
      {"selective-threshold", ParameterType::Real, "0.1",
       "with selective: re-evaluate where the element's error estimate (the largest relative difference between "
       "its nodes and itself) is at least this (0: everywhere)",
       0},
  };
  return table;
}

const ParameterSpec &selectivePowerParameter() {
  static const ParameterSpec spec = {
      "selective-power", ParameterType::Real, "1e-4",
      "with selective, on a hierarchical solution: re-evaluate the partially visible links carrying at least this "
      "fraction of the emitted power",
      kPositive};
  return spec;
}

SelectiveOptions SelectiveOptions::from(const Parameters &parameters) {
  SelectiveOptions o;
  o.enabled = parameters.flag("selective");
  o.threshold = parameters.real("selective-threshold");
  return o;
}

TwoPassRenderer::TwoPassRenderer(const RayTracer &tracer, const RenderContext &context,
                                 const SelectiveOptions &selective)
    : tracer_(tracer),
      scene_(tracer.scene()),
      solution_(requireSolution(context)),
      context_(context),
      selective_(selective),
      lights_(tracer.scene()) {}

Bands TwoPassRenderer::radiance(const Ray &ray, Sampler &rng) const {
  VisiblePoint x;
  if (!findVisiblePoint(tracer_, solution_, ray, rng, x, context_.pixelSpreadAngle)) return Bands(0.0);
  Bands L(0.0);
  if (selective_.enabled && !selectsByLinks_ && trustsSolution(x)) {
    L = radiosity(solution_, x.at) * kInvPi;  // emission included
  } else {
    L = x.material->emission + (selective_.enabled && selectsByLinks_ ? reflectedByLinks(x, rng) : reflected(x, rng));
  }
  L = x.throughput * L;
  // A sample may be negative (reichert's correction of the solution): the
  // pixel's mean is what is unbiased, and clamping samples would brighten it.
  return L.isFinite() ? L : Bands(0.0);
}

Bands TwoPassRenderer::reflectedByLinks(const VisiblePoint &x, Sampler &rng) const {
  return reflected(x, rng);
}

std::vector<std::string> TwoPassRenderer::channels() const {
  if (!selective_.enabled) return {};
  return {selectsByLinks_ ? "selective-links" : "selective-elements"};
}

Bands TwoPassRenderer::sample(const Ray &ray, Sampler &rng, Bands *values) const {
  const Bands L = radiance(ray, rng);
  if (selective_.enabled) values[0] = Bands(selectiveWork(ray));
  return L;
}

double TwoPassRenderer::selectiveWork(const Ray &ray) const {
  if (!selective_.enabled) return 0;
  Sampler rng{Pcg32()};
  VisiblePoint x;
  if (!findVisiblePoint(tracer_, solution_, ray, rng, x)) return 0;
  return trustsSolution(x) ? 0.0 : 1.0;
}

bool TwoPassRenderer::trustsSolution(const VisiblePoint &x) const {
  // The interpolated solution has no bumps: bump-mapped points are always re-evaluated.
  if (x.material->bumpTextureIndex >= 0 || x.material->normalTextureIndex >= 0) return false;
  return errorEstimate(solution_, x.at) < selective_.threshold;
}

Bands TwoPassRenderer::directLight(const VisiblePoint &x, Sampler &rng) const {
  const Bsdf bsdf(*x.material, x.hit.shadingNormal, x.hit.geometricNormal, x.wo, &x.reflectance);
  return estimateDirectLight(lights_, tracer_, x.hit, bsdf, rng, LightWeighting::Alone);
}

void TwoPassRenderer::prepareExactDirectLight() {
  exactDirect_.emplace(scene_);
  if (exactDirect_->empty() || exactDirect_->emitters().size() > kMaxExactEmitters) exactDirect_.reset();
}

std::optional<Bands> TwoPassRenderer::exactDirectLight(const VisiblePoint &x) const {
  if (!exactDirect_ || x.material->kind != MaterialKind::Lambertian ||
      dot(x.hit.shadingNormal, x.hit.geometricNormal) <= 0.999999)
    return std::nullopt;
  Bands exact;
  if (!exactDirect_->irradianceWithin(x.hit.position, x.hit.geometricNormal, kMaxExactOccluders, exact))
    return std::nullopt;
  Bands L = x.reflectance * exact * kInvPi;
  if (x.material->isTranslucent()) {
    if (!exactDirect_->irradianceWithin(x.hit.position, -x.hit.geometricNormal, kMaxExactOccluders, exact))
      return std::nullopt;
    L += x.material->transmittance * exact * kInvPi;
  }
  return L;
}

}  // namespace radiant
