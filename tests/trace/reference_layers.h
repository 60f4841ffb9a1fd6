// The sheen and clear-coat layers of trace/bsdf.h written a second time, for tests only, in
// double from the sources' own forms: the Charlie distribution with 1 - cos^2 (Estevez &
// Kulla 2017, eq. 2), their Lambda in the glTF sheen extension's GLSL form (mix() of the
// coefficient pairs), the coat as the core model's specular term with f0 0.04 (the clearcoat
// extension), and the layering of bsdf.h's "The layers". E, the sheen's albedo, comes in as
// a callable: the table is tested on its own against a quadrature of refSheen.
#pragma once

#include "tests/trace/reference_bsdf.h"

namespace photovr::test {

inline double refMix(double x, double y, double t) {
  return x * (1.0 - t) + y * t;  // GLSL mix
}

inline double refCharlieD(double cosH, double alpha) {
  const double inv = 1.0 / alpha;
  return (2.0 + inv) * std::pow(std::max(0.0, 1.0 - cosH * cosH), 0.5 * inv) / (2.0 * kRefPi);
}

inline double refCharlieL(double x, double alpha) {
  const double t = (1.0 - alpha) * (1.0 - alpha);
  const double a = refMix(21.5473, 25.3245, t), b = refMix(3.82987, 3.32435, t),
               c = refMix(0.19823, 0.16801, t), d = refMix(-1.97760, -1.27393, t),
               e = refMix(-4.32054, -4.85967, t);
  return a / (1.0 + b * std::pow(x, c)) + d * x + e;
}

inline double refCharlieLambda(double cosTheta, double alpha) {
  const double c = std::abs(cosTheta);
  return c < 0.5 ? std::exp(refCharlieL(c, alpha))
                 : std::exp(2.0 * refCharlieL(0.5, alpha) - refCharlieL(1.0 - c, alpha));
}

// The sheen BRDF with colour 1 at perceptual roughness r (alpha = r^2, floored as GGX's).
inline double refSheen(double r, const glm::dvec3& wo, const glm::dvec3& wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  const double alpha = refAlpha(r);
  const glm::dvec3 h = glm::normalize(wo + wi);
  const double g = 1.0 / (1.0 + refCharlieLambda(wo.z, alpha) + refCharlieLambda(wi.z, alpha));
  return refCharlieD(h.z, alpha) * g / (4.0 * wo.z * wi.z);
}

struct RefLayers {
  RefMaterial base;
  glm::dvec3 sheenColor{0.0};
  double sheenRoughness = 0.0;
  double coat = 0.0, coatRoughness = 0.0;
  glm::dvec3 coatNormal{0.0, 0.0, 1.0};  // the coat's own normal (KHR_materials_clearcoat's map)
};

// coat + A_c (sheen + A_s base) for reflection (both directions above the surface).
template <class Albedo>
glm::dvec3 refLayered(const RefLayers& m, const Albedo& sheenAlbedo, const glm::dvec3& wo,
                      const glm::dvec3& wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return glm::dvec3(0.0);
  const glm::dvec3 h = glm::normalize(wo + wi);
  const double fc = refSchlick(glm::dvec3(0.04), glm::dot(wo, h)).x;
  const double ac = refAlpha(m.coatRoughness);
  // The coat about its own normal: a direction behind it has no coat lobe, and the filter
  // takes |cos| there (symmetric in wo and wi).
  const glm::dvec3 nc = glm::normalize(m.coatNormal);
  const double cwo = glm::dot(wo, nc), cwi = glm::dot(wi, nc);
  double coat = 0.0;
  if (cwo > 0.0 && cwi > 0.0)
    coat = m.coat * fc * refGgxD(glm::dot(h, nc), ac) * refSmithG1(cwo, ac) * refSmithG1(cwi, ac) /
           (4.0 * cwo * cwi);
  const double coatFilter = (1.0 - m.coat * refSchlick(glm::dvec3(0.04), std::abs(cwo)).x) *
                            (1.0 - m.coat * refSchlick(glm::dvec3(0.04), std::abs(cwi)).x);
  const double eV = sheenAlbedo(wo.z, m.sheenRoughness), eL = sheenAlbedo(wi.z, m.sheenRoughness);
  const double sMax = std::max({m.sheenColor.r, m.sheenColor.g, m.sheenColor.b});
  const double sheenFilter =
      sMax > 0.0 ? std::min(1.0 - sMax * std::min(eV, 1.0), 1.0 - sMax * std::min(eL, 1.0)) : 1.0;
  const glm::dvec3 sheen =
      m.sheenColor * refSheen(m.sheenRoughness, wo, wi) / std::max({1.0, eV, eL});
  return glm::dvec3(coat) + coatFilter * (sheen + sheenFilter * refBrdf(m.base, wo, wi));
}

}  // namespace photovr::test
