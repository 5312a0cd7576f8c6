// `path` — the unbiased reference path tracer, the ground truth every other
// method in Radiant is measured against.
//
// Estimator (Veach 1997, ch. 9; pbrt-v4 PathIntegrator): at every non-delta
// vertex, next-event estimation to a point on an emitter (chosen by power,
// render/light_sampler.h) and a BSDF-sampled continuation; emission found by the
// continuation is weighted against the light sample with the power heuristic,
// so each light path is counted once in expectation. Emitters are one-sided:
// only their front (counter-clockwise) side emits. Russian roulette after three
// bounces, with survival probability tied to the path throughput, keeps the
// estimator unbiased without a depth limit.
//
// Parameters: max depth in bounces (0 = unlimited; 1 = direct light only; a
// positive value truncates paths, biasing
// the image dark, for debugging only).
#include "render/path_tracer.h"

#include "radiosity/solution_query.h"
#include "raytrace/surface_detail.h"
#include "render/bsdf.h"
#include "render/caustic_photons.h"
#include "render/light_sampler.h"
#include "render/registry.h"
#include "util/sampling.h"

namespace radiant {

namespace {

class PathTracer final : public Renderer {
 public:
  PathTracer(const RayTracer &tracer, const RenderContext &context, int maxDepth)
      : tracer_(tracer),
        scene_(tracer.scene()),
        lights_(tracer.scene()),
        maxDepth_(maxDepth),
        irradiance_(context.irradiance),
        caustics_(context.caustics),
        readCaustics_(context.specularLastLight ? context.specularLastLight : context.caustics),
        solution_(context.solution),
        readDepth_(context.solution ? context.readSolutionDepth : 0) {
    meter_.name = "irradiance meter";
    meter_.diffuse = Bands(1.0);
  }

  Bands radiance(const Ray &cameraRay, Sampler &rng) const override { return trace(cameraRay, rng, nullptr); }

  /// "control": this path read the solution where radiance() would stop,
  /// from the same numbers (so the two differ only past that vertex); paths
  /// that end before it give the control their radiance (multipass,
  /// render/control_variate.h). Asked for it, the path goes on past the read.
  std::vector<std::string> channels() const override { return {"control"}; }
  Bands sample(const Ray &cameraRay, Sampler &rng, Bands *values) const override {
    Bands &control = values[0];
    bool controlSet = false;
    const Bands L = trace(cameraRay, rng, readDepth_ > 0 ? &control : nullptr, &controlSet);
    if (!controlSet) control = L;
    return L;
  }

 private:
  /// One path; with `control`, the solution-reading estimate is stored there
  /// (and `*controlSet` raised) at the read vertex, and the path continues.
  Bands trace(const Ray &cameraRay, Sampler &rng, Bands *control, bool *controlSet = nullptr) const {
    Bands L(0.0), throughput(1.0);
    Ray ray = cameraRay;
    bool countEmissionFully = true;  // camera rays and delta bounces: no light sample competed
    double previousBsdfPdf = 0;
    Vec3 previousPosition = ray.origin;
    bool metered = false;  // irradiance: the meter is placed at the first non-delta vertex
    // Multipass (render/multipass.h): non-specular vertices so far, specular
    // bounces since the last one, and whether that one took its caustics from the map.
    int diffuseVertices = 0, specularSinceDiffuse = 0;
    bool lastUsedMap = false;

    for (int depth = 0;; ++depth) {
      Hit hit;
      if (!tracer_.intersect(ray, hit)) break;  // no environment light: the world outside is black
      const Material &material = scene_.materials[hit.material];
      // Texture and bump maps (raytrace/surface_detail.h): ρ(x) and the bumped shading normal.
      Bands diffuse = material.diffuse;
      if (material.hasSurfaceDetail()) {
        // The finest texels, unfiltered: the pixel's own samples integrate the texture
        // over its footprint, so the reference stays exact (review: prefiltering blurred it).
        const SurfaceDetail detail = surfaceDetail(scene_, hit, 0.0);
        diffuse = detail.diffuse;
        hit.shadingNormal = detail.shadingNormal;
      }
      Vec3 wo = -ray.direction;
      // Irradiance: at the first surface that is not a mirror or glass, a white
      // Lambertian meter replaces the material, and π·(reflected radiance of
      // ρ = 1) = ∫L cos dω is the irradiance; the surface's own emission is not
      // light arriving. Rough glass is looked through, as the two-pass methods do.
      const bool meterHere = irradiance_ && !metered && !material.isSpecular();

      // Emission seen by this ray (front side only). With a caustic map, light
      // that left a non-specular vertex through specular bounces to reach an
      // emitter (L S+ D, seen from the eye) is the map's: not counted here.
      const bool causticPath = lastUsedMap && specularSinceDiffuse > 0;
      if (material.isEmitter() && dot(wo, hit.geometricNormal) > 0 && !meterHere && !causticPath) {
        double weight = 1.0;
        if (!countEmissionFully) {
          double cosLight = dot(wo, hit.geometricNormal);
          double distance2 = sqr(length(hit.position - previousPosition));
          double lightPdf = lights_.pdfArea(hit.triangle) * distance2 / cosLight;
          weight = powerHeuristic(previousBsdfPdf, lightPdf);
        }
        L += throughput * material.emission * weight;
      }
      if (maxDepth_ > 0 && depth >= maxDepth_) break;  // max depth counts bounces
      if (!material.isDelta()) {
        // Rough glass ends a specular chain (the caustic map holds only chains
        // of delta bounces) but is no vertex to read the solution at: it holds
        // nothing there (ρ = 0).
        specularSinceDiffuse = 0;
        const bool readable = !material.isSpecular();
        if (readable) ++diffuseVertices;
        const Vec3 facing = dot(wo, hit.geometricNormal) >= 0 ? hit.geometricNormal : -hit.geometricNormal;
        // Multipass's low-frequency passes: past readDepth non-specular bounces
        // the solution's reflected radiosity stands for the rest of the path (as rushmeier does at depth 1).
        if (readable && readDepth_ > 0 && diffuseVertices == readDepth_ + 1) {
          Bands read = L + throughput * readSolution(hit, wo, diffuse);
          if (readCaustics_) read += throughput * readCaustics_->reflectedRadiance(hit.position, facing, diffuse);
          if (!control) return read.isFinite() ? read : Bands(0.0);
          *control = read.isFinite() ? read : Bands(0.0), *controlSet = true;
        }
        // The map holds the caustic a Lambertian point reflects; at a glossy
        // point its lobe's share would be lost, so there the path tracer finds
        // the whole caustic itself, as without a map (review).
        lastUsedMap = caustics_ && (meterHere || material.kind == MaterialKind::Lambertian);
        if (lastUsedMap)
          L += throughput * caustics_->reflectedRadiance(hit.position, facing, meterHere ? Bands(1.0) : diffuse);
      } else {
        ++specularSinceDiffuse;
      }

      Bsdf bsdf(meterHere ? meter_ : material, hit.shadingNormal, hit.geometricNormal, wo,
                meterHere ? nullptr : &diffuse);
      if (meterHere) throughput *= kPi, metered = true;

      if (!bsdf.isDelta() && !lights_.empty())
        L += throughput * estimateDirectLight(lights_, tracer_, hit, bsdf, rng, LightWeighting::PowerHeuristic);

      BsdfSample s;
      double uLobe = rng.next(), u1 = rng.next(), u2 = rng.next();
      if (!bsdf.sample(uLobe, u1, u2, s)) break;
      throughput *= s.weight;
      if (throughput.max() <= 0) break;
      countEmissionFully = s.isDelta;
      previousBsdfPdf = s.pdf;
      previousPosition = hit.position;

      if (depth >= 3) {
        double survive = std::min(0.95, throughput.max());
        if (rng.next() >= survive) break;
        throughput *= 1.0 / survive;
      }
      ray = tracer_.spawnRay(hit.position, hit.geometricNormal, s.wi);
      if (depth > 100000) break;  // a path this long carries nothing measurable; guards against NaN loops
    }
    return L.isFinite() ? L : Bands(0.0);
  }

  const RayTracer &tracer_;
  const Scene &scene_;
  LightSampler lights_;
  int maxDepth_;
  /// What the solution says the hit reflects towards wo, as radiance
  /// (radiosity/solution_query.h: front side only, eq. 9.11 with ρ(x) = rho).
  Bands readSolution(const Hit &hit, const Vec3 &wo, const Bands &rho) const {
    SolutionPoint at;
    if (!locateHit(*solution_, hit, wo, at)) return Bands(0.0);
    applySurfaceDetail(*solution_, scene_.materials[hit.material], rho, at);
    return reflectedRadiance(*solution_, at);
  }

  bool irradiance_;
  const CausticPhotonMap *caustics_;
  const CausticPhotonMap *readCaustics_;  ///< read with the solution: specularLastLight, else caustics_
  const Solution *solution_;
  int readDepth_;
  Material meter_;  ///< Lambertian, ρ = 1: the irradiance meter
};

std::unique_ptr<Renderer> createPathTracer(const RayTracer &tracer, const RenderContext &context,
                                           const Parameters &parameters) {
  return std::make_unique<PathTracer>(tracer, context, int(parameters.integer("max-depth")));
}

}  // namespace

const ParameterSpec &maxDepthParameter() {
  static const ParameterSpec spec = {"max-depth",
                                     ParameterType::Integer,
                                     "0",
                                     "maximum bounces (0: unlimited, Russian roulette ends paths; 1: direct light "
                                     "only). A limit biases the image dark: for debugging",
                                     0,
                                     1 << 20};
  return spec;
}

RendererInfo pathMethod() {
  return {"path",
          "unbiased reference path tracer (NEE + MIS, Russian roulette)",
          {maxDepthParameter()},
          &createPathTracer,
          nullptr,
          false,
          true};
}

}  // namespace radiant
