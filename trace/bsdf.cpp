#include "trace/bsdf.h"

#include <algorithm>

#include "trace/bsdf_lanes.h"
#include "trace/sampling.h"

namespace photovr {
namespace {

float sinTheta2(const glm::vec3& w) {
  return w.x * w.x + w.y * w.y;
}

// The half-vector of a reflection pair; false when wo and wi cancel.
bool halfVector(const glm::vec3& wo, const glm::vec3& wi, glm::vec3& h) {
  h = wo + wi;
  const float len2 = glm::dot(h, h);
  if (!(len2 > 0.0f)) return false;
  h *= 1.0f / std::sqrt(len2);
  return true;
}

}  // namespace

float roughnessToAlpha(float roughness) {
  return lanes::roughnessToAlphaOf(roughness);
}

float ggxD(const glm::vec3& h, float alpha) {
  return lanes::ggxDOf(lanes::V3<float>{h.x, h.y, h.z}, alpha);
}

float ggxLambda(const glm::vec3& w, float alpha) {
  const float cos2 = w.z * w.z;
  if (cos2 == 0.0f) return std::numeric_limits<float>::infinity();
  const float tan2 = sinTheta2(w) / cos2;
  return 0.5f * (-1.0f + std::sqrt(1.0f + alpha * alpha * tan2));
}

float ggxG1OverCos(const glm::vec3& w, float alpha) {
  return lanes::ggxG1OverCosOf(lanes::V3<float>{w.x, w.y, w.z}, alpha);
}

float ggxG1(const glm::vec3& w, float alpha) {
  return ggxG1OverCos(w, alpha) * std::max(w.z, 0.0f);
}

glm::vec3 fresnelSchlick(const glm::vec3& f0, float cosTheta) {
  return fresnelSchlick(f0, 1.0f, cosTheta);
}

glm::vec3 fresnelSchlick(const glm::vec3& f0, float f90, float cosTheta) {
  const lanes::V3<float> f =
      lanes::fresnelSchlickOf(lanes::V3<float>{f0.x, f0.y, f0.z}, f90, cosTheta);
  return {f.x, f.y, f.z};
}

float fresnelDielectric(float cosThetaI, float eta) {
  const float c = std::clamp(cosThetaI, 0.0f, 1.0f);
  const float sin2T = (1.0f - c * c) / (eta * eta);  // Snell's law
  if (!(sin2T < 1.0f)) return 1.0f;                  // total internal reflection (or NaN eta)
  const float cosT = safeSqrt(1.0f - sin2T);
  const float parallel = (eta * c - cosT) / (eta * c + cosT);
  const float perpendicular = (c - eta * cosT) / (c + eta * cosT);
  return 0.5f * (parallel * parallel + perpendicular * perpendicular);
}

glm::vec3 sampleGgxVndf(const glm::vec3& wo, float alpha, glm::vec2 u) {
  const lanes::V3<float> h = lanes::ggxVndfOf(lanes::V3<float>{wo.x, wo.y, wo.z}, alpha, u.x, u.y);
  return {h.x, h.y, h.z};
}

float ggxVndfPdf(const glm::vec3& wo, const glm::vec3& h, float alpha) {
  return ggxG1OverCos(wo, alpha) * std::max(0.0f, glm::dot(wo, h)) * ggxD(h, alpha);
}

float specularProbability(const BsdfParams& p, const glm::vec3& wo) {
  return prepareBsdf(p, wo).specularProbability;
}

glm::vec3 evalBsdf(const BsdfParams& p, const glm::vec3& wo, const glm::vec3& wi) {
  const BsdfLobes f = evalBsdfLobes(p, wo, wi);
  return f.specular + f.diffuse;
}

BsdfLobes evalBsdfLobes(const BsdfParams& p, const glm::vec3& wo, const glm::vec3& wi) {
  return evalBsdfAndPdf(prepareBsdf(p, wo), wi).f;
}

glm::vec3 diffuseAlbedo(const BsdfParams& p) {
  const float transmission = std::clamp(p.transmission, 0.0f, 1.0f);
  return (1.0f - std::clamp(p.metallic, 0.0f, 1.0f)) * (1.0f - transmission) * p.baseColor;
}

namespace {

// Karis 2014, EnvBRDFApprox (after Lazarov 2013): the split-sum scale A and bias B of a GGX
// lobe, F = f0 A + f90 B.
glm::vec2 envBrdfApprox(float roughness, float nv) {
  const float r = isFinite(roughness) ? std::clamp(roughness, 0.0f, 1.0f) : 0.0f;
  const glm::vec4 c0(-1.0f, -0.0275f, -0.572f, 0.022f), c1(1.0f, 0.0425f, 1.04f, -0.04f);
  const glm::vec4 q = r * c0 + c1;
  const float a004 = std::min(q.x * q.x, std::exp2(-9.28f * nv)) * q.x + q.y;
  return glm::vec2(-1.04f, 1.04f) * a004 + glm::vec2(q.z, q.w);
}

}  // namespace

namespace {

// specularAlbedo at the clamped cosine 'nv', with p's vertex 'v'.
glm::vec3 specularAlbedoOf(const BsdfVertex& v, const BsdfParams& p, float nv) {
  // The glass lobe's part is its Fresnel split at the macro-surface; the layers add their
  // albedos and filter the base's as "The layers" in bsdf.h do.
  const glm::vec2 ab = envBrdfApprox(p.roughness, nv);
  glm::vec3 albedo = v.f0 * ab.x + v.f90 * ab.y;
  if (v.glass > 0.0f) {
    const float fr = fresnelDielectric(nv, v.eta);
    albedo = v.brdfWeight * albedo + v.glass * (fr + (1.0f - fr) * v.tint);
  }
  if (!v.layered) return albedo;
  const float sheen = std::min(v.sheenAlbedoWo, 1.0f);
  const float through = 1.0f - v.coatFresnelWo;
  const glm::vec2 coat = envBrdfApprox(p.clearcoatRoughness, nv);
  return through * ((1.0f - v.sheenMax * sheen) * albedo + sheen * v.sheenColor) +
         glm::vec3(v.coat * (kDielectricF0 * coat.x + coat.y));
}

}  // namespace

glm::vec3 specularAlbedo(const BsdfParams& p, float cosThetaO) {
  const float nv = std::clamp(cosThetaO, 0.0f, 1.0f);
  return specularAlbedoOf(prepareBsdf(p, glm::vec3(0.0f, safeSqrt(1.0f - nv * nv), nv)), p, nv);
}

glm::vec3 specularAlbedo(const BsdfVertex& v, const BsdfParams& p, float cosThetaO) {
  if (v.layered) return specularAlbedo(p, cosThetaO);
  return specularAlbedoOf(v, p, std::clamp(cosThetaO, 0.0f, 1.0f));
}

float pdfBsdf(const BsdfParams& p, const glm::vec3& wo, const glm::vec3& wi) {
  return pdfBsdf(prepareBsdf(p, wo), wi);
}

namespace {

// The lobe is chosen by u.x < p, and u.x is then stretched back over [0, 1) within the
// chosen lobe's share (as pbrt-v4's SampleDiscrete returns uRemapped): the samples that
// pick a lobe keep the 2D stratification of the sampler's (0, 2)-net in that lobe, where a
// separate lobe number would hand each lobe a random subset of the net's points (issue 18:
// at 256 spp, 8 seeds, bench_sampler's relMSE ratio to the random sampler went from 3.26x
// to 3.39x on textured-gltf, 1.14x to 1.26x on metal-gltf). Capped below 1, as the
// samplers promise u < 1.
float remapLobeNumber(float ux, float p, bool firstLobe) {
  const float stretched = firstLobe ? ux / p : (ux - p) / (1.0f - p);
  return std::min(stretched, 0x1.fffffep-1f);
}

}  // namespace

BsdfSample sampleBsdf(const BsdfParams& p, const glm::vec3& wo, glm::vec2 u) {
  return sampleBsdf(prepareBsdf(p, wo), u);
}

namespace {

// Reflection probability within the glass lobe: Fresnel at the macro-surface, kept within
// [0.05, 0.95] so that both halves are sampled wherever their microfacets contribute (under
// total internal reflection at the macro-surface rough microfacets still refract). f cos /
// pdf of a half is then F(wo.h) / P_R or (1 - F(wo.h)) / (1 - P_R) times bounded factors.
constexpr float kMinGlassHalfProbability = 0.05f;
// Relative indices within this of 1 are index-matched (prepareGlass): 1e-4 keeps Walter's
// half-vector, |wo + eta wi| >= ~|eta - 1|, well above float rounding of unit vectors.
constexpr float kIndexMatched = 1e-4f;

// The glass lobe's value and density at wi, the density given the lobe was chosen.
struct LobeEval {
  glm::vec3 f{0.0f};
  float pdf = 0.0f;
};

LobeEval glassReflection(const BsdfVertex& v, const glm::vec3& wi) {
  glm::vec3 h;
  if (!halfVector(v.wo, wi, h)) return {};
  const float d = ggxD(h, v.alpha);
  const float fr = fresnelDielectric(glm::dot(v.wo, h), v.eta);
  const float g = v.g1OverCosWo * d * 0.25f;  // D G1(wo) / (4 wo.z), the VNDF through reflection
  return {glm::vec3(fr * g * ggxG1OverCos(wi, v.alpha)), v.reflectProbability * g};
}

// Thin wall: the reflection lobe at wi mirrored back above the surface, weighted by 1 - F.
LobeEval glassThinTransmission(const BsdfVertex& v, const glm::vec3& wi) {
  const glm::vec3 mirrored(wi.x, wi.y, -wi.z);
  glm::vec3 h;
  if (!halfVector(v.wo, mirrored, h)) return {};
  const float d = ggxD(h, v.alpha);
  const float t = 1.0f - fresnelDielectric(glm::dot(v.wo, h), v.eta);
  const float g = v.g1OverCosWo * d * 0.25f;
  return {v.tint * (t * g * ggxG1OverCos(mirrored, v.alpha)), (1.0f - v.reflectProbability) * g};
}

// Refraction into the far side: Walter et al. 2007's generalised half-vector h ~ wo + eta
// wi (eq. 16), its Jacobian |wi.h| / (wi.h + wo.h / eta)^2 (eq. 17, pbrt-v4's form) and the
// BTDF of eq. 21 with the 1 / eta^2 of radiance transport.
LobeEval glassRefraction(const BsdfVertex& v, const glm::vec3& wi) {
  glm::vec3 h = v.wo + v.eta * wi;
  const float len2 = glm::dot(h, h);
  if (!(len2 > 0.0f)) return {};
  h *= (h.z < 0.0f ? -1.0f : 1.0f) / std::sqrt(len2);
  const float oh = glm::dot(v.wo, h), ih = glm::dot(wi, h);
  if (!(oh > 0.0f && ih < 0.0f)) return {};  // each direction on its own side of h
  const float denom = ih + oh / v.eta;
  const float denom2 = denom * denom;
  if (!(denom2 > 0.0f)) return {};
  const float d = ggxD(h, v.alpha);
  const float t = 1.0f - fresnelDielectric(oh, v.eta);
  const float vndf = v.g1OverCosWo * oh * d;  // D_wo(h), Heitz 2018 eq. 1
  const float jacobian = -ih / denom2;
  const float g1i = ggxG1OverCos(-wi, v.alpha);
  const glm::vec3 f = v.tint * (t * vndf * g1i * jacobian / (v.eta * v.eta));
  return {f, (1.0f - v.reflectProbability) * vndf * jacobian};
}

LobeEval glassLobe(const BsdfVertex& v, const glm::vec3& wi) {
  if (wi.z > 0.0f) return glassReflection(v, wi);
  if (!(wi.z < 0.0f)) return {};
  return v.thinWalled ? glassThinTransmission(v, wi) : glassRefraction(v, wi);
}

// A direction from the glass lobe, or none (wi = 0): VNDF normal, then reflect, mirror or
// refract (Snell, pbrt-v4's Refract) as u.x chose.
glm::vec3 sampleGlassDirection(const BsdfVertex& v, glm::vec2 u) {
  const bool reflect = u.x < v.reflectProbability;
  u.x = remapLobeNumber(u.x, v.reflectProbability, reflect);
  const glm::vec3 h = sampleGgxVndf(v.wo, v.alpha, u);
  const float oh = glm::dot(v.wo, h);
  const glm::vec3 r = 2.0f * oh * h - v.wo;
  // A half's direction on the other half's side is no sample: the pdf would count it there.
  if (reflect || v.thinWalled) {
    if (!(r.z > 0.0f)) return glm::vec3(0.0f);
    return reflect ? r : glm::vec3(r.x, r.y, -r.z);
  }
  const float sin2T = (1.0f - oh * oh) / (v.eta * v.eta);
  if (!(sin2T < 1.0f)) return glm::vec3(0.0f);  // total internal reflection at this facet
  const float cosT = safeSqrt(1.0f - sin2T);
  const glm::vec3 t = -v.wo / v.eta + (oh / v.eta - cosT) * h;
  return t.z < 0.0f ? t : glm::vec3(0.0f);
}

glm::vec3 sampleBrdfDirection(const BsdfVertex& v, glm::vec2 u, bool& specularLobe) {
  specularLobe = u.x < v.specularProbability;
  u.x = remapLobeNumber(u.x, v.specularProbability, specularLobe);
  if (!specularLobe) return sampleCosineHemisphere(u);
  const glm::vec3 h = sampleGgxVndf(v.wo, v.alpha, u);
  return 2.0f * glm::dot(v.wo, h) * h - v.wo;
}

// The glass lobe's share and probabilities; the BRDF's metallic re-weighted so the metal
// keeps its share (bsdf.h, "The glass lobe").
void prepareGlass(const BsdfParams& p, float metallic, BsdfVertex& v, float& brdfMetallic) {
  const float transmission =
      isFinite(p.transmission) ? std::clamp(p.transmission, 0.0f, 1.0f) : 0.0f;
  v.glass = (1.0f - metallic) * transmission;
  brdfMetallic = metallic;
  if (!(v.glass > 0.0f)) {
    v.glass = 0.0f;
    return;
  }
  v.brdfWeight = 1.0f - v.glass;
  brdfMetallic = v.brdfWeight > 0.0f ? std::min(1.0f, metallic / v.brdfWeight) : 0.0f;
  v.eta = isFinite(p.eta) ? std::clamp(p.eta, 1e-3f, 1e3f) : 1.5f;
  // An index-matched interface (relative index 1: ior 1, or a volume inside a medium of
  // its own index) does not bend light, and Walter's refraction half-vector wo + eta wi
  // vanishes for the one direction it sends light in (every refracted path was lost). It
  // is sampled as a thin wall, whose transmission continues straight for a smooth surface;
  // a rough one still spreads that lobe, where a true index match would not.
  v.thinWalled = p.thinWalled || std::abs(v.eta - 1.0f) < kIndexMatched;
  const float fr = fresnelDielectric(v.wo.z, v.eta);
  v.reflectProbability = std::clamp(fr, kMinGlassHalfProbability, 1.0f - kMinGlassHalfProbability);
}

void prepareLayers(const BsdfParams& p, BsdfVertex& v);

}  // namespace

BsdfVertex prepareBsdf(const BsdfParams& p, const glm::vec3& wo) {
  // Clamp into the documented ranges; NaN parameters become 0 (std::clamp keeps NaN). The
  // BRDF's terms are the lanes' template (trace/bsdf_lanes.h), so the BSDF stage's
  // vertices get these bits.
  const lanes::V3<float> base = lanes::unitColourOf(v3Of(p.baseColor));
  BsdfVertex v;
  v.wo = wo;
  v.alpha = lanes::roughnessToAlphaOf(p.roughness);
  v.tint = vec3Of(base);
  float metallic;
  prepareGlass(p, lanes::unitNumberOf(p.metallic), v, metallic);
  setBrdfTerms(v, lanes::brdfTermsOf(base, metallic, lanes::unitColourOf(v3Of(p.dielectricF0)),
                                     lanes::unitNumberOf(p.dielectricF90), v.alpha, v3Of(wo)));
  if (v.glass > 0.0f) {
    // Lobe weights as in specularProbability: the BRDF's estimate lum(F) + lum((1 - F)
    // diffuse), the glass lobe's F + (1 - F) lum(tint), both at the macro-surface.
    const float fr = fresnelDielectric(wo.z, v.eta);
    const float brdf =
        luminance(v.fresnelWo) + luminance((glm::vec3(1.0f) - v.fresnelWo) * v.diffuse);
    const float glass = fr + (1.0f - fr) * luminance(v.tint);
    const float wg = v.glass * glass, wb = v.brdfWeight * brdf;
    v.glassProbability = wg + wb > 0.0f ? wg / (wg + wb) : 1.0f;
    if (!(v.brdfWeight > 0.0f)) v.glassProbability = 1.0f;
  }
  prepareLayers(p, v);
  return v;
}

namespace {

// The base: the metallic-roughness BRDF and the glass lobe, without sheen and coat.
BsdfEval evalBase(const BsdfVertex& v, const glm::vec3& wi) {
  if (v.glass == 0.0f) return evalBrdf(v, wi);
  if (!(v.wo.z > 0.0f)) return {};
  BsdfEval e = evalBrdf(v, wi);
  e.f.diffuse *= v.brdfWeight;
  e.f.specular *= v.brdfWeight;
  e.pdf *= 1.0f - v.glassProbability;
  const LobeEval g = glassLobe(v, wi);
  e.f.specular += v.glass * g.f;
  e.pdf += v.glassProbability * g.pdf;
  return e;
}

BsdfSample sampleBase(const BsdfVertex& v, glm::vec2 u) {
  if (v.glass == 0.0f) return sampleBrdf(v, u);
  if (!(v.wo.z > 0.0f)) return {};
  BsdfSample s;
  if (u.x < v.glassProbability) {
    u.x = remapLobeNumber(u.x, v.glassProbability, true);
    s.wi = sampleGlassDirection(v, u);
    s.specularLobe = true;
  } else {
    u.x = remapLobeNumber(u.x, v.glassProbability, false);
    s.wi = sampleBrdfDirection(v, u, s.specularLobe);
    // A reflection below the surface is no sample (the glass lobe's pdf would count it).
    if (!(s.wi.z > 0.0f)) return {};
  }
  // The pdf is recomputed from wi rather than carried from the lobe's sampler, so a
  // sample's pdf is exactly what pdfBsdf() later says about the same direction (MIS).
  const BsdfEval e = evalBsdfAndPdf(v, s.wi);
  if (!(e.pdf > 0.0f) || !isFinite(e.pdf)) return {};
  s.pdf = e.pdf;
  s.fDiffuse = e.f.diffuse;
  s.f = e.f.total();
  s.weight = s.f * (std::abs(s.wi.z) / s.pdf);
  return s;
}

// KHR_materials_clearcoat's Fresnel: Schlick with f0 0.04, f90 1.
float coatFresnel(float cosTheta) {
  return fresnelSchlick(glm::vec3(kDielectricF0), cosTheta).x;
}

// The coat and sheen lobes at wi and the factor A_c A_s that filters the base (bsdf.h,
// "The layers"), with the layers' own densities.
struct LayerEval {
  glm::vec3 coat{0.0f}, sheen{0.0f};  // coat is c F D G / (4 ..); sheen already times A_c
  float baseFilter = 1.0f;            // A_c A_s
  float coatPdf = 0.0f, sheenPdf = 0.0f;
};

// wi in the coat's frame.
glm::vec3 toCoat(const BsdfVertex& v, const glm::vec3& wi) {
  return v.coatTilted ? Frame::fromZ(v.coatNormal).toLocal(wi) : wi;
}

LayerEval evalLayers(const BsdfVertex& v, const glm::vec3& wi) {
  LayerEval e;
  const float cosI = std::min(std::abs(wi.z), 1.0f);
  const glm::vec3 coatWi = toCoat(v, wi);
  const float coatIn = 1.0f - v.coat * coatFresnel(std::min(std::abs(coatWi.z), 1.0f));
  const float coatFilter = (1.0f - v.coatFresnelWo) * coatIn;
  float sheenFilter = 1.0f, sheenNormal = 1.0f;
  if (v.sheenMax > 0.0f) {
    const float eV = v.sheenAlbedoWo, eL = sheenAlbedo(cosI, v.sheenRoughness);
    sheenFilter =
        std::min(1.0f - v.sheenMax * std::min(eV, 1.0f), 1.0f - v.sheenMax * std::min(eL, 1.0f));
    sheenNormal = 1.0f / std::max({1.0f, eV, eL});
  }
  e.baseFilter = coatFilter * sheenFilter;
  glm::vec3 h;
  if (!(wi.z > 0.0f) || !halfVector(v.wo, wi, h)) return e;
  glm::vec3 hc = h;
  if (v.coat > 0.0f && v.coatWo.z > 0.0f && coatWi.z > 0.0f &&
      (!v.coatTilted || halfVector(v.coatWo, coatWi, hc))) {
    const float d = ggxD(hc, v.coatAlpha);
    const float g = v.coatG1OverCosWo * d * 0.25f;  // the VNDF through reflection
    e.coat = glm::vec3(v.coat * coatFresnel(glm::dot(v.coatWo, hc)) * g *
                       ggxG1OverCos(coatWi, v.coatAlpha));
    e.coatPdf = g;
  }
  if (v.sheenMax > 0.0f) {
    const float g = 1.0f / (1.0f + v.sheenLambdaWo + charlieLambda(wi.z, v.sheenAlpha));
    const float f = charlieD(h, v.sheenAlpha) * g * sheenNormal / (4.0f * v.wo.z * wi.z);
    e.sheen = coatFilter * f * v.sheenColor;
    e.sheenPdf = uniformHemispherePdf();
  }
  return e;
}

// The layers' choice: each lobe by its albedo estimate at wo, as the base's lobes are.
void prepareLayers(const BsdfParams& p, BsdfVertex& v) {
  const auto unit = [](float x) { return isFinite(x) ? std::clamp(x, 0.0f, 1.0f) : 0.0f; };
  v.coat = unit(p.clearcoat);
  v.coatWo = v.wo;
  const glm::vec3 n = p.coatNormal;
  if (v.coat > 0.0f && n != glm::vec3(0.0f, 0.0f, 1.0f) && isFinite(n) && n.z > 0.0f) {
    v.coatTilted = true;
    v.coatNormal = glm::normalize(n);
    v.coatWo = Frame::fromZ(v.coatNormal).toLocal(v.wo);
  }
  v.sheenColor = glm::clamp(isFinite(p.sheenColor) ? p.sheenColor : glm::vec3(0.0f), 0.0f, 1.0f);
  v.sheenMax = std::max({v.sheenColor.r, v.sheenColor.g, v.sheenColor.b});
  v.layered = v.coat > 0.0f || v.sheenMax > 0.0f;
  if (!v.layered) return;
  const float nv = v.wo.z;
  v.coatAlpha = roughnessToAlpha(p.clearcoatRoughness);
  // Seen from behind the coat's own normal (a tilted coat), the coat lobe is 0 and is not
  // sampled; its Fresnel still filters what passes, at |cos|, so the BSDF stays reciprocal.
  const bool coatFacesWo = v.coatWo.z > 0.0f;
  v.coatG1OverCosWo = coatFacesWo ? ggxG1OverCos(v.coatWo, v.coatAlpha) : 0.0f;
  v.coatFresnelWo = v.coat * coatFresnel(std::abs(v.coatWo.z));
  v.sheenRoughness = unit(p.sheenRoughness);
  v.sheenAlpha = sheenRoughnessToAlpha(v.sheenRoughness);
  v.sheenLambdaWo = charlieLambda(nv, v.sheenAlpha);
  v.sheenAlbedoWo = sheenAlbedo(nv, v.sheenRoughness);
  // Estimates: the coat's c F_c(n.v), the sheen's (1 - c F_c) lum(sheenColor) E, the
  // base's (1 - c F_c)(1 - max(sheen) E) times 1 (its albedo is not known here, and a dark
  // base under a coat must still be sampled where the coat is weak).
  const float through = 1.0f - v.coatFresnelWo;
  const float coat = coatFacesWo ? v.coatFresnelWo : 0.0f;
  const float sheen = through * luminance(v.sheenColor) * std::min(v.sheenAlbedoWo, 1.0f);
  const float base = through * (1.0f - v.sheenMax * std::min(v.sheenAlbedoWo, 1.0f));
  const float sum = coat + sheen + base;
  if (!(sum > 0.0f)) return;
  v.coatProbability = coat / sum;
  v.sheenProbability = sheen / sum;
}

}  // namespace

BsdfEval evalBsdfAndPdf(const BsdfVertex& v, const glm::vec3& wi) {
  BsdfEval e = evalBase(v, wi);
  if (!v.layered) return e;
  if (!(v.wo.z > 0.0f)) return {};
  const LayerEval l = evalLayers(v, wi);
  const float pBase = 1.0f - v.coatProbability - v.sheenProbability;
  e.f.diffuse *= l.baseFilter;
  e.f.specular = e.f.specular * l.baseFilter + l.sheen + l.coat;
  e.pdf = pBase * e.pdf + v.sheenProbability * l.sheenPdf + v.coatProbability * l.coatPdf;
  return e;
}

float pdfBsdf(const BsdfVertex& v, const glm::vec3& wi) {
  if (v.layered || v.glass != 0.0f) return evalBsdfAndPdf(v, wi).pdf;
  // Inlined, the BSDF's value is left out: only the pdf is used.
  return lanes::evalBrdfPartsOf(brdfVertexOf(v), v3Of(wi)).value.pdf;
}

BsdfSample sampleBsdfDirection(const BsdfVertex& v, glm::vec2 u) {
  if (v.layered || v.glass != 0.0f) return sampleBsdf(v, u);
  if (!(v.wo.z > 0.0f)) return {};
  BsdfSample s;
  s.wi = sampleBrdfDirection(v, u, s.specularLobe);
  s.pdf = pdfBsdf(v, s.wi);
  return s.pdf > 0.0f && isFinite(s.pdf) ? s : BsdfSample{};
}

BsdfVertex prepareBsdfPdf(const BsdfParams& p, const glm::vec3& wo, float specularProbability) {
  BsdfVertex v;
  if (plainBsdf(p)) {
    v.wo = wo;
    v.alpha = roughnessToAlpha(p.roughness);
    v.g1OverCosWo = ggxG1OverCos(wo, v.alpha);
  } else {
    v = prepareBsdf(p, wo);
  }
  v.specularProbability = specularProbability;
  return v;
}

BsdfSample sampleBsdf(const BsdfVertex& v, glm::vec2 u) {
  if (!v.layered) return sampleBase(v, u);
  if (!(v.wo.z > 0.0f)) return {};
  const float pCoat = v.coatProbability, pLayers = pCoat + v.sheenProbability;
  BsdfSample s;
  if (u.x < pLayers) {
    const bool coat = u.x < pCoat;
    u.x = coat ? remapLobeNumber(u.x, pCoat, true)
               : std::min((u.x - pCoat) / v.sheenProbability, 0x1.fffffep-1f);
    if (coat) {
      const glm::vec3 h = sampleGgxVndf(v.coatWo, v.coatAlpha, u);
      const glm::vec3 coatWi = 2.0f * glm::dot(v.coatWo, h) * h - v.coatWo;
      // Below the coat's own horizon the coat has no density (evalLayers): no sample.
      if (v.coatTilted && !(coatWi.z > 0.0f)) return {};
      s.wi = v.coatTilted ? Frame::fromZ(v.coatNormal).toWorld(coatWi) : coatWi;
    } else {
      s.wi = sampleUniformHemisphere(u);
    }
    if (!(s.wi.z > 0.0f)) return {};
    s.specularLobe = true;
  } else {
    u.x = remapLobeNumber(u.x, pLayers, false);
    const BsdfSample base = sampleBase(v, u);
    if (!base.valid()) return {};
    s.wi = base.wi;
    s.specularLobe = base.specularLobe;
  }
  const BsdfEval e = evalBsdfAndPdf(v, s.wi);
  if (!(e.pdf > 0.0f) || !isFinite(e.pdf)) return {};
  s.pdf = e.pdf;
  s.fDiffuse = e.f.diffuse;
  s.f = e.f.total();
  s.weight = s.f * (std::abs(s.wi.z) / s.pdf);
  return s;
}

}  // namespace photovr
