// `flat` and `interpolate` — the radiosity solution itself, displayed (C&W §9.2).
//
// The eye ray's first diffuse hit shows the solution's radiance B/π there:
// `flat` the element's constant value (the mesh made visible), `interpolate`
// the value interpolated from the element's nodes (bilinear on quads,
// barycentric on triangles; Gouraud shading of the mesh), continuous inside a
// patch. Both include the progressive solver's ambient term.
//
// Mirrors and glass seen from the eye are followed (ideal reflection and
// refraction, Fresnel-weighted choice) until a diffuse surface is reached,
// as the per-pixel methods do; the back side of a face, which the one-sided
// radiosity mesh does not represent, is black.
#include "render/radiosity_display.h"

#include "radiosity/solution.h"
#include "render/bsdf.h"
#include "util/error.h"

namespace radiant {

namespace {

class RadiosityDisplay final : public Renderer {
 public:
  RadiosityDisplay(const RayTracer &tracer, const Solution &solution, bool interpolate)
      : tracer_(tracer), solution_(solution), interpolate_(interpolate) {}

  Bands radiance(const Ray &cameraRay, Pcg32 &rng) const override {
    const Scene &scene = tracer_.scene();
    Ray ray = cameraRay;
    Bands throughput(1.0);
    for (int bounce = 0; bounce < kMaxSpecularBounces; ++bounce) {
      Hit hit;
      if (!tracer_.intersect(ray, hit)) return Bands(0.0);
      const Material &material = scene.materials[hit.material];
      Vec3 wo = -ray.direction;
      if (material.isDelta()) {
        Bsdf bsdf(material, hit.shadingNormal, hit.geometricNormal, wo);
        BsdfSample s;
        double uLobe = rng.next(), u1 = rng.next(), u2 = rng.next();
        if (!bsdf.sample(uLobe, u1, u2, s)) return Bands(0.0);
        throughput *= s.weight;
        ray = tracer_.spawnRay(hit.position, hit.geometricNormal, s.wi);
        continue;
      }
      if (dot(wo, hit.geometricNormal) <= 0) return Bands(0.0);  // back side: not in the solution
      int32_t patch = solution_.mesh.patchOfFace[hit.face];
      if (patch < 0) return Bands(0.0);
      MeshLocation location = solution_.mesh.locate(hit.face, hit.position);
      Bands radiosity = interpolate_ ? solution_.interpolatedRadiosity(location)
                                     : solution_.displayRadiosity(location.element);
      return throughput * radiosity * kInvPi;
    }
    return Bands(0.0);
  }

 private:
  static constexpr int kMaxSpecularBounces = 64;
  const RayTracer &tracer_;
  const Solution &solution_;
  bool interpolate_;
};

const Solution &requireSolution(const RendererOptions &options) {
  if (!options.solution) throw InputError(InputLocation{"--method"}, "this method needs a radiosity solution");
  return *options.solution;
}

}  // namespace

std::unique_ptr<Renderer> createFlatRadiosityDisplay(const RayTracer &tracer, const RendererOptions &options) {
  return std::make_unique<RadiosityDisplay>(tracer, requireSolution(options), false);
}

std::unique_ptr<Renderer> createInterpolatedRadiosityDisplay(const RayTracer &tracer, const RendererOptions &options) {
  return std::make_unique<RadiosityDisplay>(tracer, requireSolution(options), true);
}

}  // namespace radiant
