// The material model written out a second time, for tests only, straight from the formulas
// of ../shared/reference/thesis.md (Moschos 2019, sec. 2.1.2) and the diffuse balance that
// trace/bsdf.h documents. It shares no code with trace/bsdf.cpp: double precision, the
// textbook forms (1 - (n.h)^2 instead of h.x^2 + h.y^2, the thesis's G1 written with a^2
// + (1 - a^2)(n.v)^2, pow(., 5) for Schlick), and no BsdfVertex, so a scaled term or a
// wrong exponent in the renderer shows as a disagreement with this file. After the model:
// quadrature rules for integrating its lobes, sharp ones included (Gauss-Legendre, over
// half-vectors), used by tests/trace/bsdf_reference_test.cpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace photovr::test {

// Parameters in their documented ranges, [0,1] (trace/bsdf.h's BsdfParams): the renderer
// clamps out-of-range values, this does not, except roughness as refAlpha says.
struct RefMaterial {
  glm::dvec3 baseColor{1.0};
  double metallic = 0.0;
  double roughness = 1.0;  // glTF perceptual roughness
};

inline constexpr double kRefPi = 3.14159265358979323846;

// glTF 2.0 Appendix B: alpha = roughness^2; floored at 0.045^2 as trace/bsdf.h documents
// (Filament's MIN_PERCEPTUAL_ROUGHNESS). Out-of-range roughness clamps into [0,1] and NaN
// becomes 0 (roughnessToAlpha's documented contract; std::clamp alone would keep NaN).
inline double refAlpha(double roughness) {
  const double r = roughness > 0.0 ? std::min(roughness, 1.0) : 0.0;
  return std::max(r * r, 0.045 * 0.045);
}

// Thesis: D(h) = a^2 / (pi ((n.h)^2 (a^2 - 1) + 1)^2), n = +z. In double the cancellation
// of 1 - (n.h)^2 (1 - a^2) near the peak costs ~2e-16 / a^2 relative (D ~ t^-2): < 6e-11
// for every a >= 0.045^2.
inline double refGgxD(double cosH, double a) {
  if (cosH <= 0.0) return 0.0;
  const double a2 = a * a;
  const double t = cosH * cosH * (a2 - 1.0) + 1.0;
  return a2 / (kRefPi * t * t);
}

// Thesis: G1(v) = 2 (n.v) / ((n.v) + sqrt(a^2 + (1 - a^2)(n.v)^2)).
inline double refSmithG1(double cosV, double a) {
  if (cosV <= 0.0) return 0.0;
  const double a2 = a * a;
  return 2.0 * cosV / (cosV + std::sqrt(a2 + (1.0 - a2) * cosV * cosV));
}

// Thesis: F = F0 + (1 - F0)(1 - v.h)^5.
inline glm::dvec3 refSchlick(const glm::dvec3& f0, double cosTheta) {
  return f0 + (glm::dvec3(1.0) - f0) * std::pow(1.0 - std::clamp(cosTheta, 0.0, 1.0), 5.0);
}

inline glm::dvec3 refF0(const RefMaterial& m) {
  return glm::mix(glm::dvec3(0.04), m.baseColor, m.metallic);  // glTF 2.0 Appendix B
}

// Thesis: f_spec = D F G / (4 (n.l)(n.v)), G = G1(l) G1(v), F at v.h.
inline glm::dvec3 refSpecular(const RefMaterial& m, const glm::dvec3& wo, const glm::dvec3& wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return glm::dvec3(0.0);
  const glm::dvec3 h = glm::normalize(wo + wi);
  const double a = refAlpha(m.roughness);
  const double g = refSmithG1(wi.z, a) * refSmithG1(wo.z, a);
  return refGgxD(h.z, a) * refSchlick(refF0(m), glm::dot(wo, h)) * g / (4.0 * wi.z * wo.z);
}

// Lambert albedo / pi, through the interface on the way in and out: (1 - F(n.v))(1 - F(n.l))
// (1 - metallic) baseColor / pi (trace/bsdf.h, evalBsdf's comment, says why this balance).
inline glm::dvec3 refDiffuse(const RefMaterial& m, const glm::dvec3& wo, const glm::dvec3& wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return glm::dvec3(0.0);
  const glm::dvec3 f0 = refF0(m), one(1.0);
  return (one - refSchlick(f0, wo.z)) * (one - refSchlick(f0, wi.z)) * (1.0 - m.metallic) *
         m.baseColor / kRefPi;
}

inline glm::dvec3 refBrdf(const RefMaterial& m, const glm::dvec3& wo, const glm::dvec3& wi) {
  return refSpecular(m, wo, wi) + refDiffuse(m, wo, wi);
}

// A direction from spherical angles, z up.
inline glm::dvec3 refDirection(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// The directional albedo of f (a callable (wo, wi) -> dvec3) for wo, by midpoint quadrature
// over the hemisphere in (cos theta, phi): d(cos theta) absorbs the sin theta of solid angle.
// Plain midpoints: a sharp lobe (small roughness) needs a grid fine enough to resolve it, or
// a quadrature of its own (refAlbedoHalfVector below).
template <class F>
glm::dvec3 refAlbedo(const F& f, const glm::dvec3& wo, int nCos, int nPhi) {
  glm::dvec3 sum(0.0);
  for (int i = 0; i < nCos; ++i) {
    const double c = (i + 0.5) / nCos;
    const double s = std::sqrt(1.0 - c * c);
    for (int j = 0; j < nPhi; ++j) {
      const double phi = 2.0 * kRefPi * (j + 0.5) / nPhi;
      const glm::dvec3 wi(s * std::cos(phi), s * std::sin(phi), c);
      sum += f(wo, wi) * c;
    }
  }
  return sum * (2.0 * kRefPi / (double(nCos) * nPhi));
}

// v rounded to float, for feeding a float implementation and this double one the same
// direction. Through volatile: GCC 12.2 at -O2 miscompiles the plain double(float(x)) of
// two SLP-vectorised lanes into a copy, dropping the rounding (seen in
// bsdf_reference_test.cpp's random points; -fno-tree-slp-vectorize restores it).
inline glm::dvec3 refToFloat(const glm::dvec3& v) {
  volatile float x = float(v.x), y = float(v.y), z = float(v.z);
  return {x, y, z};
}

// Quadrature nodes as they are, or rounded to float (refAlbedoHalfVector says when which).
enum class RefNodes { Float, Exact };
inline glm::dvec3 refNode(const glm::dvec3& v, RefNodes nodes) {
  return nodes == RefNodes::Float ? refToFloat(v) : v;
}

// The n-point Gauss-Legendre rule on [a, b], exact for polynomials of degree < 2n (Press et
// al., "Numerical Recipes", 3rd ed., sec. 4.6, gauleg: Newton's method on P_n).
struct RefRule {
  std::vector<double> x, w;
  void append(const RefRule& r) {
    x.insert(x.end(), r.x.begin(), r.x.end());
    w.insert(w.end(), r.w.begin(), r.w.end());
  }
};
inline RefRule refGaussLegendre(int n, double a, double b) {
  RefRule r{std::vector<double>(n), std::vector<double>(n)};
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double z = std::cos(kRefPi * (i + 0.75) / (n + 0.5)), dp = 1.0, dz = 1.0;
    for (int it = 0; it < 100 && std::abs(dz) > 1e-15; ++it) {
      double p1 = 1.0, p2 = 0.0;  // P_n(z), P_{n-1}(z) by the three-term recurrence
      for (int j = 0; j < n; ++j) {
        const double p3 = p2;
        p2 = p1;
        p1 = ((2.0 * j + 1.0) * z * p2 - j * p3) / (j + 1.0);
      }
      dp = n * (z * p1 - p2) / (z * z - 1.0);
      dz = p1 / dp;
      z -= dz;
    }
    r.x[i] = mid - half * z;
    r.x[n - 1 - i] = mid + half * z;
    r.w[i] = r.w[n - 1 - i] = 2.0 * half / ((1.0 - z * z) * dp * dp);
  }
  return r;
}

// Composite Gauss-Legendre: [a, b] in equal panels of width <= maxWidth, n nodes each. For
// an integrand analytic in a strip |Im x| < d the error of a panel of half-width h falls as
// rho^-2n, rho = d/h + sqrt(1 + (d/h)^2) (Trefethen, "Approximation Theory and
// Approximation Practice", ch. 19): one long panel converges slowly, panels of h ~ d fast.
inline RefRule refCompositeGauss(int n, double a, double b, double maxWidth) {
  RefRule r;
  const int panels = std::max(1, int(std::ceil((b - a) / maxWidth)));
  for (int k = 0; k < panels; ++k)
    r.append(refGaussLegendre(n, a + (b - a) * k / panels, a + (b - a) * (k + 1) / panels));
  return r;
}

// A rule on [a, b] whose nodes crowd both ends: composite Gauss-Legendre in t over [-1, 1]
// mapped by x = mid + half (3t - t^3) / 2, whose derivative vanishes at t = +-1. An
// integrand going as (x - a)^3/2 at an end (where a horizon closes a circle of azimuths)
// becomes (1 + t)^3 (2 - t)^3/2, smooth, so the rule keeps its fast convergence there.
inline RefRule refEndClusteredGauss(int n, double a, double b, int panels) {
  RefRule r = refCompositeGauss(n, -1.0, 1.0, 2.0 / panels);
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  for (size_t i = 0; i < r.x.size(); ++i) {
    const double t = r.x[i];
    r.x[i] = mid + half * 0.5 * t * (3.0 - t * t);
    r.w[i] *= half * 1.5 * (1.0 - t * t);
  }
  return r;
}

// The azimuths |phi - phi_o| < refHorizonPhi of half-vectors at theta_h whose reflection of
// wo (at theta_o from the normal) stays above the surface: wi.z = 2 (wo.h) cos theta_h -
// cos theta_o > 0 <=> cos phi > -cot theta_o cot 2 theta_h. All of them (pi) up to theta_h
// = (pi/2 - theta_o) / 2, none from (pi/2 + theta_o) / 2 on.
inline double refHorizonPhi(double thetaO, double thetaH) {
  const double s = std::sin(thetaO) * std::sin(2.0 * thetaH);
  if (!(s > 0.0)) return std::cos(2.0 * thetaH) > 0.0 ? kRefPi : 0.0;
  return std::acos(std::clamp(-std::cos(thetaO) * std::cos(2.0 * thetaH) / s, -1.0, 1.0));
}

// The rule over s = ln tan theta_h for refAlbedoHalfVector: below the horizon's entry s1,
// composite panels of width 2 (GGX is analytic in s within |Im s| < pi/2); from s1 to
// where the horizon closes, s2, the end-clustered rule.
inline RefRule refHalfVectorRule(double thetaO, double alpha, int nS) {
  const double t1 = 0.25 * kRefPi - 0.5 * thetaO, t2 = 0.25 * kRefPi + 0.5 * thetaO;
  const double s1 = std::log(std::tan(t1)), s2 = std::log(std::tan(t2));
  RefRule r = refCompositeGauss(nS, std::min(std::log(alpha), s1) - 18.0, s1, 2.0);
  if (s2 > s1) r.append(refEndClusteredGauss(nS, s1, s2, std::max(1, int((s2 - s1) / 2.0))));
  return r;
}

// The directional albedo of a lobe f (a callable (wo, wi) -> dvec3) for wo (wo.z > 0), by
// quadrature over half-vectors: for lobes too sharp for refAlbedo (roughness 0.045 is a
// lobe ~2e-3 rad wide). wi = reflect(wo, h), dwi = 4 (wo.h) dwh (Walter et al. 2007, eq.
// 14). theta_h runs over s = ln tan theta_h (dtheta = sin cos ds), in which a GGX lobe of
// any alpha is the same smooth bump: D cos dwh = tau^2 / (pi (1 + tau^2)^2) ds dphi with
// tau = tan theta_h / alpha, tails ~e^-2|s - ln alpha|, cut 18 widths out (< 1e-15 of the
// lobe). phi is integrated between the horizon's crossings (refHorizonPhi), nPhi
// Gauss-Legendre nodes, so the integrand is smooth inside every panel. With
// RefNodes::Float each node's wi is rounded to float before f sees it: a float renderer
// and a double reference integrated by this rule then see the same directions (rounding
// wi moves a sharp lobe's h by ~1e-7 / alpha relative, far more than the renderer's own
// rounding; at grazing angles 1 / cos of the half angle more). That rounding perturbs the
// rule itself by as much (~1e-5 for roughness 0.045 at 89 degrees), the same for both, so
// it cancels between them; a check of the rule's own accuracy takes RefNodes::Exact.
template <class F>
glm::dvec3 refAlbedoHalfVector(const F& f, const glm::dvec3& wo, double alpha, int nS, int nPhi,
                               RefNodes nodes = RefNodes::Float) {
  const double thetaO = std::atan2(std::hypot(wo.x, wo.y), wo.z), phiO = std::atan2(wo.y, wo.x);
  const RefRule rs = refHalfVectorRule(thetaO, alpha, nS);
  const RefRule unit = refGaussLegendre(nPhi, -1.0, 1.0);
  glm::dvec3 sum(0.0);
  for (size_t i = 0; i < rs.x.size(); ++i) {
    const double th = std::atan(std::exp(rs.x[i])), st = std::sin(th), ct = std::cos(th);
    const double phiMax = refHorizonPhi(thetaO, th);
    for (size_t j = 0; j < unit.x.size(); ++j) {
      const double phi = phiO + phiMax * unit.x[j];
      const glm::dvec3 h(st * std::cos(phi), st * std::sin(phi), ct);
      const double cosOH = glm::dot(wo, h);
      const glm::dvec3 wi = refNode(2.0 * cosOH * h - wo, nodes);
      if (!(cosOH > 0.0) || !(wi.z > 0.0)) continue;
      const double dwh = st * (st * ct) * rs.w[i] * phiMax * unit.w[j];
      sum += f(wo, wi) * (wi.z * 4.0 * cosOH * dwh);
    }
  }
  return sum;
}

}  // namespace photovr::test
