// The glass lobe of trace/bsdf.h written a second time, for tests only, from the papers'
// own forms in double: the Fresnel equations in angles (Born & Wolf; Hecht, "Optics",
// eq. 4.42-4.43: R_s = sin^2(t_t - t_i) / sin^2(t_t + t_i), R_p = tan^2(t_t - t_i) /
// tan^2(t_t + t_i)), Walter et al. 2007's BTDF with their own symbols (eq. 16, 21: i the
// light's direction on the side of index eta_i, o the viewer's on the side of eta_o), and
// the thin wall as the reflection lobe mirrored. No code shared with trace/bsdf.cpp.
#pragma once

#include "tests/trace/reference_bsdf.h"

namespace photovr::test {

// Unpolarised reflectance for light meeting the interface at cosI, from the side of index
// n1 towards n2.
inline double refFresnelAngles(double cosI, double n1, double n2) {
  cosI = std::clamp(cosI, 0.0, 1.0);
  const double ti = std::acos(cosI);
  const double sinT = n1 / n2 * std::sin(ti);
  if (sinT >= 1.0) return 1.0;
  if (ti == 0.0) {  // the limit of both terms at normal incidence
    const double r = (n1 - n2) / (n1 + n2);
    return r * r;
  }
  const double tt = std::asin(sinT);
  const double rs = std::pow(std::sin(tt - ti) / std::sin(tt + ti), 2.0);
  const double rp = std::pow(std::tan(tt - ti) / std::tan(tt + ti), 2.0);
  return 0.5 * (rs + rp);
}

struct RefGlass {
  glm::dvec3 tint{1.0};
  double roughness = 0.5;
  double eta = 1.5;  // index of wi's side over wo's (n_far / n_near)
  bool thin = false;
};

// Smith G1 on the side of w (|cos|).
inline double refG1Abs(double cosW, double a) {
  return refSmithG1(std::abs(cosW), a);
}

inline glm::dvec3 refGlassReflection(const RefGlass& g, const glm::dvec3& wo,
                                     const glm::dvec3& wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return glm::dvec3(0.0);
  const glm::dvec3 h = glm::normalize(wo + wi);
  const double a = refAlpha(g.roughness);
  const double f = refFresnelAngles(glm::dot(wo, h), 1.0, g.eta);
  return glm::dvec3(f * refGgxD(h.z, a) * refSmithG1(wo.z, a) * refSmithG1(wi.z, a) /
                    (4.0 * wo.z * wi.z));
}

inline glm::dvec3 refGlassTransmission(const RefGlass& g, const glm::dvec3& wo,
                                       const glm::dvec3& wi) {
  if (wo.z <= 0.0 || wi.z >= 0.0) return glm::dvec3(0.0);
  const double a = refAlpha(g.roughness);
  if (g.thin) {
    const glm::dvec3 m(wi.x, wi.y, -wi.z);
    const glm::dvec3 h = glm::normalize(wo + m);
    const double t = 1.0 - refFresnelAngles(glm::dot(wo, h), 1.0, g.eta);
    return g.tint *
           (t * refGgxD(h.z, a) * refSmithG1(wo.z, a) * refSmithG1(m.z, a) / (4.0 * wo.z * m.z));
  }
  // Walter eq. 16 and 21 with i = wi (eta_i = eta), o = wo (eta_o = 1).
  const double etaI = g.eta, etaO = 1.0;
  glm::dvec3 ht = -(etaI * wi + etaO * wo);
  ht = glm::normalize(ht);
  if (ht.z < 0.0) ht = -ht;
  const double ih = glm::dot(wi, ht), oh = glm::dot(wo, ht);
  if (ih * wi.z <= 0.0 || oh * wo.z <= 0.0) return glm::dvec3(0.0);  // Walter's chi+ terms
  const double f = refFresnelAngles(oh, 1.0, g.eta);
  const double gg = refG1Abs(wi.z, a) * refG1Abs(wo.z, a);
  const double denom = etaI * ih + etaO * oh;
  const double ft = std::abs(ih) * std::abs(oh) / (std::abs(wi.z) * std::abs(wo.z)) * etaO * etaO *
                    (1.0 - f) * gg * refGgxD(ht.z, a) / (denom * denom);
  return g.tint * ft;
}

inline glm::dvec3 refGlass(const RefGlass& g, const glm::dvec3& wo, const glm::dvec3& wi) {
  return wi.z > 0.0 ? refGlassReflection(g, wo, wi) : refGlassTransmission(g, wo, wi);
}

}  // namespace photovr::test
