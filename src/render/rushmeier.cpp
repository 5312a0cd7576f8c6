// `rushmeier` — per-pixel Monte Carlo reading the solution at secondary hits
// (C&W eq. 9.10; Rushmeier's 1988 thesis).
//
// At the visible point x, per camera sample:
//   L(x) = Le(x) + f·Le_s cosθx cosθs V / (r² p_A)          one point on an emitter
//               + ρ · (B(y) − E(y)) / π                      one cosine-distributed ray to y
// The secondary ray reads the interpolated solution at y and does not
// recurse. It counts only y's reflected radiosity B − E, never its emission:
// the emitter sample already accounts for direct light, so a secondary ray
// that lands on a light would otherwise count it twice. Its expectation is
// the one-bounce final gather E + ρ[E_s F(dx→s) + Σ_j (B_j − E_j) F(dx→j)],
// sharper than the element average.
//
// Specular surfaces met by the secondary ray are followed to a diffuse point
// (the solution has nothing on mirrors and glass), and an emitter reached
// through them is counted: the shadow ray cannot see a light through glass,
// so that path (L S+ D E) has no other estimator. Glossy surfaces sample
// their whole BSDF for the secondary direction.
#include "render/bsdf.h"
#include "render/registry.h"
#include "render/two_pass.h"

namespace radiant {

namespace {

class Rushmeier final : public TwoPassRenderer {
 public:
  using TwoPassRenderer::TwoPassRenderer;

 protected:
  Bands reflected(const VisiblePoint &x, Sampler &rng) const override {
    Bands L = directLight(x, rng);
    Bsdf bsdf(*x.material, x.hit.shadingNormal, x.hit.geometricNormal, x.wo, &x.reflectance);
    BsdfSample s;
    double uLobe = rng.next(), u1 = rng.next(), u2 = rng.next();
    if (!bsdf.sample(uLobe, u1, u2, s)) return L;
    return L + s.weight * gatheredRadiance(tracer_.spawnRay(x.hit.position, x.hit.geometricNormal, s.wi), rng);
  }

 private:
  /// Radiance the solution says arrives along a secondary ray: the reflected
  /// radiosity at the diffuse point it reaches, plus that point's emission
  /// only if a specular chain led there.
  Bands gatheredRadiance(const Ray &ray, Sampler &rng) const {
    VisiblePoint y;
    if (!findVisiblePoint(tracer_, solution_, ray, rng, y)) return Bands(0.0);
    Bands L = reflectedRadiance(solution_, y.at);
    if (y.specularBounces > 0) L += y.material->emission;
    return y.throughput * L;
  }
};

std::unique_ptr<Renderer> createRushmeier(const RayTracer &tracer, const RenderContext &context,
                                          const Parameters &parameters) {
  return std::make_unique<Rushmeier>(tracer, context, SelectiveOptions::from(parameters));
}

}  // namespace

RendererInfo rushmeierMethod() {
  return {"rushmeier",
          "per-pixel Monte Carlo: light sample + one secondary ray reading the solution (C&W eq. 9.10)",
          selectiveParameters(),
          &createRushmeier,
          nullptr,
          true};
}

}  // namespace radiant
