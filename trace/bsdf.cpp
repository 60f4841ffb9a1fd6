#include "trace/bsdf.h"

#include <algorithm>

#include "trace/sampling.h"

namespace photovr {
namespace {

// The parameters in the form the lobes use, derived once per call.
struct Lobes {
  float alpha;
  glm::vec3 f0;       // specular reflectance at normal incidence
  glm::vec3 diffuse;  // (1 - metallic) baseColor, the Lambert albedo before Fresnel
};

Lobes lobes(const BsdfParams& p) {
  // Clamp into the documented ranges; NaN parameters become 0 (std::clamp keeps NaN).
  const glm::vec3 base =
      glm::clamp(glm::vec3(isFinite(p.baseColor) ? p.baseColor : glm::vec3(0.0f)), 0.0f, 1.0f);
  const float metallic = isFinite(p.metallic) ? std::clamp(p.metallic, 0.0f, 1.0f) : 0.0f;
  return {roughnessToAlpha(p.roughness), glm::mix(glm::vec3(kDielectricF0), base, metallic),
          (1.0f - metallic) * base};
}

float sinTheta2(const glm::vec3& w) {
  return w.x * w.x + w.y * w.y;
}

glm::vec3 specular(const Lobes& l, const glm::vec3& wo, const glm::vec3& wi, const glm::vec3& h) {
  const glm::vec3 f = fresnelSchlick(l.f0, glm::dot(wo, h));
  return f * (ggxD(h, l.alpha) * ggxG1OverCos(wo, l.alpha) * ggxG1OverCos(wi, l.alpha) * 0.25f);
}

glm::vec3 diffuse(const Lobes& l, const glm::vec3& wo, const glm::vec3& wi) {
  const glm::vec3 one(1.0f);
  return (one - fresnelSchlick(l.f0, wo.z)) * (one - fresnelSchlick(l.f0, wi.z)) * l.diffuse *
         kInvPi;
}

float specularProbability(const Lobes& l, const glm::vec3& wo) {
  const glm::vec3 f = fresnelSchlick(l.f0, wo.z);
  const float spec = luminance(f);
  const float diff = luminance((glm::vec3(1.0f) - f) * l.diffuse);
  if (diff <= 0.0f) return 1.0f;
  return spec / (spec + diff);
}

// The half-vector of a reflection pair; false when wo and wi cancel.
bool halfVector(const glm::vec3& wo, const glm::vec3& wi, glm::vec3& h) {
  h = wo + wi;
  const float len2 = glm::dot(h, h);
  if (!(len2 > 0.0f)) return false;
  h *= 1.0f / std::sqrt(len2);
  return true;
}

float pdf(const Lobes& l, const glm::vec3& wo, const glm::vec3& wi) {
  glm::vec3 h;
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f) || !halfVector(wo, wi, h)) return 0.0f;
  const float pSpec = specularProbability(l, wo);
  // Visible-normal density mapped through reflection, dwi = 4 (wo.h) dh (Heitz 2018,
  // eq. 17): G1(wo) D(h) / (4 wo.z), with wo.h > 0 here since both lie above the surface.
  const float specPdf = ggxG1OverCos(wo, l.alpha) * ggxD(h, l.alpha) * 0.25f;
  return pSpec * specPdf + (1.0f - pSpec) * cosineHemispherePdf(wi.z);
}

}  // namespace

float roughnessToAlpha(float roughness) {
  const float r = roughness > 0.0f ? std::min(roughness, 1.0f) : 0.0f;  // NaN -> 0
  return std::max(r * r, kMinAlpha);
}

float ggxD(const glm::vec3& h, float alpha) {
  if (!(h.z > 0.0f)) return 0.0f;
  const float a2 = alpha * alpha;
  const float t = h.z * h.z + sinTheta2(h) / a2;
  return 1.0f / (kPi * a2 * t * t);
}

float ggxLambda(const glm::vec3& w, float alpha) {
  const float cos2 = w.z * w.z;
  if (cos2 == 0.0f) return std::numeric_limits<float>::infinity();
  const float tan2 = sinTheta2(w) / cos2;
  return 0.5f * (-1.0f + std::sqrt(1.0f + alpha * alpha * tan2));
}

float ggxG1OverCos(const glm::vec3& w, float alpha) {
  if (!(w.z > 0.0f)) return 0.0f;
  // sqrt(a^2 + (1 - a^2) cos^2) = sqrt(a^2 sin^2 + cos^2) for unit w.
  const float root = std::sqrt(alpha * alpha * sinTheta2(w) + w.z * w.z);
  return 2.0f / (w.z + root);
}

float ggxG1(const glm::vec3& w, float alpha) {
  return ggxG1OverCos(w, alpha) * std::max(w.z, 0.0f);
}

glm::vec3 fresnelSchlick(const glm::vec3& f0, float cosTheta) {
  const float m = 1.0f - std::clamp(cosTheta, 0.0f, 1.0f);
  const float m2 = m * m;
  return f0 + (glm::vec3(1.0f) - f0) * (m2 * m2 * m);
}

glm::vec3 sampleGgxVndf(const glm::vec3& wo, float alpha, glm::vec2 u) {
  // Sec. 3.2: stretch wo to the hemisphere configuration (alpha = 1).
  const glm::vec3 vh = glm::normalize(glm::vec3(alpha * wo.x, alpha * wo.y, wo.z));
  // Sec. 4.1: an orthonormal basis around vh, any basis when vh = +z.
  const float lensq = vh.x * vh.x + vh.y * vh.y;
  const glm::vec3 t1 =
      lensq > 0.0f ? glm::vec3(-vh.y, vh.x, 0.0f) / std::sqrt(lensq) : glm::vec3(1, 0, 0);
  const glm::vec3 t2 = glm::cross(vh, t1);
  // Sec. 4.2: a uniform point on the projected disk, warped to its visible half.
  const float r = std::sqrt(u.x);
  const float phi = 2.0f * kPi * u.y;
  const float p1 = r * std::cos(phi);
  float p2 = r * std::sin(phi);
  const float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * safeSqrt(1.0f - p1 * p1) + s * p2;
  // Sec. 4.3: project onto the hemisphere; sec. 3.4: unstretch.
  const glm::vec3 nh = p1 * t1 + p2 * t2 + safeSqrt(1.0f - p1 * p1 - p2 * p2) * vh;
  return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, std::max(0.0f, nh.z)));
}

float ggxVndfPdf(const glm::vec3& wo, const glm::vec3& h, float alpha) {
  return ggxG1OverCos(wo, alpha) * std::max(0.0f, glm::dot(wo, h)) * ggxD(h, alpha);
}

float specularProbability(const BsdfParams& p, const glm::vec3& wo) {
  return specularProbability(lobes(p), wo);
}

glm::vec3 evalBsdf(const BsdfParams& p, const glm::vec3& wo, const glm::vec3& wi) {
  glm::vec3 h;
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f) || !halfVector(wo, wi, h)) return glm::vec3(0.0f);
  const Lobes l = lobes(p);
  return specular(l, wo, wi, h) + diffuse(l, wo, wi);
}

BsdfLobes evalBsdfLobes(const BsdfParams& p, const glm::vec3& wo, const glm::vec3& wi) {
  glm::vec3 h;
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f) || !halfVector(wo, wi, h)) return {};
  const Lobes l = lobes(p);
  return {diffuse(l, wo, wi), specular(l, wo, wi, h)};
}

glm::vec3 diffuseAlbedo(const BsdfParams& p) {
  return (1.0f - std::clamp(p.metallic, 0.0f, 1.0f)) * p.baseColor;
}

glm::vec3 specularAlbedo(const BsdfParams& p, float cosThetaO) {
  // Karis 2014, EnvBRDFApprox (after Lazarov 2013): scale and bias of F0.
  const glm::vec3 f0 =
      glm::mix(glm::vec3(kDielectricF0), p.baseColor, std::clamp(p.metallic, 0.0f, 1.0f));
  const float r = std::clamp(p.roughness, 0.0f, 1.0f), nv = std::clamp(cosThetaO, 0.0f, 1.0f);
  const glm::vec4 c0(-1.0f, -0.0275f, -0.572f, 0.022f), c1(1.0f, 0.0425f, 1.04f, -0.04f);
  const glm::vec4 q = r * c0 + c1;
  const float a004 = std::min(q.x * q.x, std::exp2(-9.28f * nv)) * q.x + q.y;
  const glm::vec2 ab = glm::vec2(-1.04f, 1.04f) * a004 + glm::vec2(q.z, q.w);
  return f0 * ab.x + ab.y;
}

float pdfBsdf(const BsdfParams& p, const glm::vec3& wo, const glm::vec3& wi) {
  return pdf(lobes(p), wo, wi);
}

BsdfSample sampleBsdf(const BsdfParams& p, const glm::vec3& wo, glm::vec2 u, float uLobe) {
  if (!(wo.z > 0.0f)) return {};
  const Lobes l = lobes(p);
  BsdfSample s;
  s.specularLobe = uLobe < specularProbability(l, wo);
  if (s.specularLobe) {
    const glm::vec3 h = sampleGgxVndf(wo, l.alpha, u);
    s.wi = 2.0f * glm::dot(wo, h) * h - wo;
  } else {
    s.wi = sampleCosineHemisphere(u);
  }
  // The pdf is recomputed from wi rather than carried from the lobe's sampler, so a
  // sample's pdf is exactly what pdfBsdf() later says about the same direction (MIS).
  s.pdf = pdf(l, wo, s.wi);
  glm::vec3 h;
  if (!(s.pdf > 0.0f) || !isFinite(s.pdf) || !halfVector(wo, s.wi, h)) return {};
  s.f = specular(l, wo, s.wi, h) + diffuse(l, wo, s.wi);
  s.weight = s.f * (s.wi.z / s.pdf);
  return s;
}

}  // namespace photovr
