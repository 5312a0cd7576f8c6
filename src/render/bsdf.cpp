#include "render/bsdf.h"

#include "util/sampling.h"

namespace radiant {

double fresnelDielectric(double cosThetaI, double eta) {
  cosThetaI = std::clamp(cosThetaI, 0.0, 1.0);
  double sin2ThetaT = (1 - cosThetaI * cosThetaI) / (eta * eta);
  if (sin2ThetaT >= 1) return 1;  // total internal reflection
  double cosThetaT = std::sqrt(1 - sin2ThetaT);
  double rParallel = (eta * cosThetaI - cosThetaT) / (eta * cosThetaI + cosThetaT);
  double rPerpendicular = (cosThetaI - eta * cosThetaT) / (cosThetaI + eta * cosThetaT);
  return 0.5 * (rParallel * rParallel + rPerpendicular * rPerpendicular);
}

Bsdf::Bsdf(const Material &material, const Vec3 &shadingNormal, const Vec3 &geometricNormal, const Vec3 &wo,
           const Bands *diffuse)
    : material_(material), diffuse_(diffuse ? *diffuse : material.diffuse) {
  bool woOnFront = dot(wo, geometricNormal) >= 0;
  entering_ = woOnFront;
  // Opaque surfaces reflect on both sides (the Cornell blocks are seen from
  // outside, walls from inside): orient the frame towards the viewer. Glass
  // keeps both sides distinct through `entering_`.
  Vec3 n = woOnFront ? shadingNormal : -shadingNormal;
  geometricNormal_ = woOnFront ? geometricNormal : -geometricNormal;
  frame_ = Frame::fromNormal(n);
  woLocal_ = frame_.toLocal(wo);
}

bool Bsdf::sameHemisphere(const Vec3 &wi) const {
  // The geometric normal decides what is reflection: a shading normal may tilt
  // a direction under the real surface, which would leak light through it.
  return dot(wi, geometricNormal_) > 0;
}

double Bsdf::specularLobeProbability() const {
  if (material_.kind != MaterialKind::Glossy) return 0;
  double d = diffuse_.average(), s = material_.specular.average();
  return d + s > 0 ? s / (d + s) : 0;
}

double Bsdf::transmissionLobeProbability() const {
  if (!material_.isTranslucent() || material_.isDelta()) return 0;
  const double t = material_.transmittance.average();
  const double r = diffuse_.average() + (material_.kind == MaterialKind::Glossy ? material_.specular.average() : 0);
  return t / (t + r);
}

bool Bsdf::transmits(const Vec3 &wiWorld, Vec3 &wiLocal) const {
  // Diffuse transmission: wi on the other side of the surface, below both
  // the geometric and the shading plane.
  if (!material_.isTranslucent() || material_.isDelta() || dot(wiWorld, geometricNormal_) >= 0) return false;
  wiLocal = frame_.toLocal(wiWorld);
  return wiLocal.z < 0 && woLocal_.z > 0;
}

bool Bsdf::roughDielectric(const Vec3 &wiWorld, Bands &f, double &pdf) const {
  // Walter, Marschner, Li & Torrance 2007 (eqs. 20–21, 38), in the form of
  // pbrt-v4's DielectricBxDF rough branch: GGX D, separable Smith G, the
  // facet normal wm from the (generalised) half vector. The frame's normal is
  // on the side of wo, so wo.z > 0, and η = η_far / η_near.
  f = Bands(0.0);
  pdf = 0;
  const Vec3 &wo = woLocal_;
  const Vec3 wi = frame_.toLocal(wiWorld);
  // Reflection or refraction by the geometric normal; the shading normal must agree.
  const bool reflect = sameHemisphere(wiWorld);
  if (wo.z <= 0 || wi.z == 0 || reflect != (wi.z > 0)) return false;
  const double alpha = material_.transmissionRoughness, eta = etaAcross();
  Vec3 wm = reflect ? wi + wo : wo + wi * eta;
  const double length2 = dot(wm, wm);
  if (!(length2 > 0)) return false;
  wm = wm / std::sqrt(length2);
  if (wm.z < 0) wm = -wm;
  // Only facets that face both directions (Walter's χ⁺ factors).
  const double cosOM = dot(wo, wm), cosIM = dot(wi, wm);
  if (cosOM <= 0 || (reflect ? cosIM <= 0 : cosIM >= 0)) return false;
  const double fresnel = fresnelDielectric(cosOM, eta);
  const double d = ggxD(wm, alpha), g = ggxG1(wo, alpha) * ggxG1(wi, alpha);
  const double facetPdf = d * wm.z;  // sampleGgxNormal draws wm with density D·cos θm
  if (reflect) {
    f = Bands(d * g * fresnel / (4 * wi.z * wo.z));
    pdf = fresnel * facetPdf / (4 * cosOM);
  } else {
    // dwm/dwi = |wi·wm| / (wi·wm + wo·wm/η)²; the radiance leaving into the
    // near medium is scaled by (η_near/η_far)² = 1/η², as in the smooth case.
    const double denominator = sqr(cosIM + cosOM / eta);
    f = material_.specular * ((1 - fresnel) * d * g * cosOM * -cosIM / (wo.z * -wi.z * denominator) / (eta * eta));
    pdf = (1 - fresnel) * facetPdf * -cosIM / denominator;
  }
  return pdf > 0 && std::isfinite(pdf);
}

Bands Bsdf::evaluate(const Vec3 &wiWorld) const {
  if (material_.isRoughDielectric()) {
    Bands f;
    double p;
    roughDielectric(wiWorld, f, p);
    return f;
  }
  if (Vec3 through; transmits(wiWorld, through)) return material_.transmittance * kInvPi;
  if (material_.isDelta() || !sameHemisphere(wiWorld)) return Bands(0.0);
  Vec3 wi = frame_.toLocal(wiWorld);
  if (wi.z <= 0 || woLocal_.z <= 0) return Bands(0.0);
  Bands f = diffuse_ * kInvPi;
  if (material_.kind == MaterialKind::Glossy) {
    // Torrance–Sparrow with GGX D and separable Smith G; the lobe's reflectance
    // is the constant `specular` (no Fresnel), so ρ_d + ρ_s ≤ 1 bounds the albedo.
    Vec3 h = normalize(wi + woLocal_);
    double g = ggxG1(wi, material_.roughness) * ggxG1(woLocal_, material_.roughness);
    f += material_.specular * (ggxD(h, material_.roughness) * g / (4 * wi.z * woLocal_.z));
  }
  return f;
}

double Bsdf::pdf(const Vec3 &wiWorld) const {
  if (material_.isRoughDielectric()) {
    Bands f;
    double p;
    return roughDielectric(wiWorld, f, p) ? p : 0.0;
  }
  const double pTransmit = transmissionLobeProbability();
  if (Vec3 through; transmits(wiWorld, through)) return pTransmit * cosineHemispherePdf(-through.z);
  if (material_.isDelta() || !sameHemisphere(wiWorld)) return 0;
  Vec3 wi = frame_.toLocal(wiWorld);
  if (wi.z <= 0 || woLocal_.z <= 0) return 0;
  double pSpecular = specularLobeProbability() * (1 - pTransmit);
  double p = (1 - pTransmit) * (1 - specularLobeProbability()) * cosineHemispherePdf(wi.z);
  if (pSpecular > 0) {
    Vec3 h = normalize(wi + woLocal_);
    double dotWoH = dot(woLocal_, h);
    if (dotWoH > 0) p += pSpecular * ggxD(h, material_.roughness) * h.z / (4 * dotWoH);
  }
  return p;
}

bool Bsdf::sample(double uLobe, double u1, double u2, BsdfSample &out) const {
  out = BsdfSample{};
  switch (material_.kind) {
    case MaterialKind::Mirror: {
      out.wi = frame_.toWorld({-woLocal_.x, -woLocal_.y, woLocal_.z});
      out.weight = material_.specular;
      out.isDelta = true;
      return sameHemisphere(out.wi);
    }
    case MaterialKind::Dielectric: {
      if (material_.isRoughDielectric()) {
        // A facet normal by D·cos θm, then reflection with probability
        // F(wo·wm), refraction through that facet otherwise (total internal
        // reflection: F = 1). f, pdf and the weight come from roughDielectric,
        // so sample(), evaluate() and pdf() cannot disagree.
        if (woLocal_.z <= 0) return false;
        const double eta = etaAcross();
        const Vec3 wm = sampleGgxNormal(u1, u2, material_.transmissionRoughness);
        const double cosOM = dot(woLocal_, wm);
        if (cosOM <= 0) return false;
        const bool reflect = uLobe < fresnelDielectric(cosOM, eta);
        Vec3 wi;
        if (reflect) {
          wi = wm * (2 * cosOM) - woLocal_;
        } else {
          const double sin2T = (1 - cosOM * cosOM) / (eta * eta);
          if (sin2T >= 1) return false;
          wi = -woLocal_ / eta + wm * (cosOM / eta - std::sqrt(1 - sin2T));
        }
        // Off a steep facet to the wrong side: lost (pdf() counts each side's own lobe only).
        if (reflect ? wi.z <= 0 : wi.z >= 0) return false;
        out.wi = frame_.toWorld(normalize(wi));
        Bands f;
        if (!roughDielectric(out.wi, f, out.pdf)) return false;
        out.weight = f * (std::abs(dot(out.wi, frame_.normal)) / out.pdf);
        out.isTransmission = !reflect;
        return true;
      }
      // Smooth glass (pbrt-v4 DielectricBxDF): reflect with probability F,
      // refract otherwise, so the weight is 1 apart from the colour filter and
      // the (η_i/η_t)² radiance scaling across the interface.
      double eta = entering_ ? material_.ior : 1.0 / material_.ior;
      double cosI = woLocal_.z;
      double fresnel = fresnelDielectric(cosI, eta);
      out.isDelta = true;
      if (uLobe < fresnel) {
        out.wi = frame_.toWorld({-woLocal_.x, -woLocal_.y, woLocal_.z});
        out.weight = Bands(1.0);
        return true;
      }
      double sin2T = (1 - cosI * cosI) / (eta * eta);
      double cosT = std::sqrt(std::max(0.0, 1 - sin2T));
      Vec3 wt = -woLocal_ / eta + Vec3{0, 0, woLocal_.z / eta - cosT};
      out.wi = frame_.toWorld(normalize(wt));
      out.weight = material_.specular / (eta * eta);
      out.isTransmission = true;
      return dot(out.wi, geometricNormal_) < 0;
    }
    case MaterialKind::Lambertian:
    case MaterialKind::Glossy: {
      if (woLocal_.z <= 0) return false;
      if (const double pTransmit = transmissionLobeProbability(); pTransmit > 0) {
        // Diffuse transmission with probability pTransmit: cosine-weighted on the far side.
        if (uLobe < pTransmit) {
          Vec3 wi = sampleCosineHemisphere(u1, u2);
          wi.z = -wi.z;
          out.wi = frame_.toWorld(wi);
          out.pdf = pdf(out.wi);
          if (out.pdf <= 0) return false;
          out.weight = evaluate(out.wi) * (-wi.z / out.pdf);
          out.isTransmission = true;
          return true;
        }
        uLobe = (uLobe - pTransmit) / (1 - pTransmit);
      }
      double pSpecular = specularLobeProbability();
      Vec3 wi;
      if (uLobe < pSpecular) {
        Vec3 h = sampleGgxNormal(u1, u2, material_.roughness);
        wi = h * (2 * dot(woLocal_, h)) - woLocal_;
      } else {
        wi = sampleCosineHemisphere(u1, u2);
      }
      if (wi.z <= 0) return false;
      out.wi = frame_.toWorld(wi);
      out.pdf = pdf(out.wi);
      if (out.pdf <= 0) return false;
      out.weight = evaluate(out.wi) * (wi.z / out.pdf);
      return true;
    }
  }
  return false;
}

}  // namespace radiant
