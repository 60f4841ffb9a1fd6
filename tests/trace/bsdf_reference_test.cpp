// Independent references for the BSDF (issue 17): evalBsdf and its terms against the
// thesis's formulas written a second time in double (reference_bsdf.h), sharing no code
// with trace/bsdf.cpp. Pointwise at random points, then integrated: the GGX normalisation,
// Heitz's projected-area identity and the lobes' directional albedos, each by a
// deterministic quadrature in a variable where the lobe is smooth at any roughness.
//
// Float tolerances are first-order rounding-error bounds (Higham, "Accuracy and Stability
// of Numerical Algorithms", 2nd ed., ch. 3) in units of u = 2^-24, the unit roundoff of
// float; the quadratures' own errors are far below them (each says why).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/trace/reference_bsdf.h"
#include "trace/bsdf.h"
#include "trace/sampling.h"

namespace photovr {
namespace {

using test::kRefPi;
using test::RefMaterial;

constexpr double kU = 0x1p-24;  // float's unit roundoff

// Error bounds of the renderer's float lobes against the exact lobes at the same (float)
// inputs, in u, of the form |f - ref| <= k u (|ref| + S), S the lobe with its Fresnel
// factors set to 1. Every factor but Fresnel is a product, quotient, square root or sum of
// positive terms, so its relative error is the count of its roundings (Higham, Lemma 3.1):
// D ~48 u (h normalised: ~6 u a component, D ~ |h|^-4, t^2 of ~20 u, a^2 and pi ~4 u),
// G1/cos ~8 u each (with the inputs' own |w|^2 = 1 +- u), the products ~4 u. Fresnel
// terms lie in [0,1] but are not relatively accurate: 1 - F cancels at grazing angles and
// F = m^5 of an F0 = 0 channel has a relative sensitivity 5/m to m = 1 - cos, so their
// error is absolute, ~65 u for F(v.h) (cos v.h ~10 u off through h) and ~14 u for each
// 1 - F(n.w). Hence specular ~70 u |ref| + 65 u S, diffuse ~6 u |ref| + 28 u S; the bounds
// below have ~2x margin for second-order terms and operation order.
constexpr double kSpecularUlps = 128.0;
constexpr double kDiffuseUlps = 64.0;

// The lobes' parts of f with Fresnel set to 1, the S of the bounds above: specular =
// D G / (4 cos cos) (a white metal's specular lobe, F0 = 1), diffuse = (1 - m) base / pi.
double specularScale(const RefMaterial& m, const glm::dvec3& wo, const glm::dvec3& wi) {
  return test::refSpecular({glm::dvec3(1.0), 1.0, m.roughness}, wo, wi).r;
}
double diffuseScale(const RefMaterial& m, const glm::dvec3& wo, const glm::dvec3& wi, int c) {
  return wo.z > 0.0 && wi.z > 0.0 ? (1.0 - m.metallic) * m.baseColor[c] / kRefPi : 0.0;
}

RefMaterial refOf(const BsdfParams& p) {
  return {glm::dvec3(p.baseColor), double(p.metallic), double(p.roughness)};
}

// The direction at theta degrees from the normal in the xz-plane, exact or rounded to float.
glm::dvec3 incident(double thetaDegrees, test::RefNodes nodes = test::RefNodes::Float) {
  const double t = thetaDegrees * kRefPi / 180.0;
  return test::refNode({std::sin(t), 0.0, std::cos(t)}, nodes);
}

// --- 1. Pointwise, at random points. -----------------------------------------------------

// The two lobes, for comparing a renderer's and a reference's.
struct Lobes {
  glm::dvec3 diffuse{0.0}, specular{0.0}, total{0.0};  // total: evalBsdf (renderer only)
};
using RendererLobes = std::function<Lobes(const BsdfParams&, glm::vec3, glm::vec3)>;
using ReferenceLobes =
    std::function<Lobes(const RefMaterial&, const glm::dvec3&, const glm::dvec3&)>;

Lobes rendererLobes(const BsdfParams& p, glm::vec3 wo, glm::vec3 wi) {
  const BsdfLobes f = evalBsdfLobes(p, wo, wi);
  return {glm::dvec3(f.diffuse), glm::dvec3(f.specular), glm::dvec3(evalBsdf(p, wo, wi))};
}
Lobes referenceLobes(const RefMaterial& m, const glm::dvec3& wo, const glm::dvec3& wi) {
  return {test::refDiffuse(m, wo, wi), test::refSpecular(m, wo, wi)};
}

// std::mt19937 is specified to the bit (C++ [rand.predef]); the distributions are not, so
// the conversion to [0,1) is written here and the points are the same on every platform.
class Points {
 public:
  explicit Points(uint32_t seed) : g_(seed) {}
  double uniform() { return g_() * 0x1p-32; }
  float pick(std::initializer_list<float> special) {  // half the time a special value
    if (uniform() >= 0.5) return float(uniform());
    return special.begin()[std::min(size_t(uniform() * special.size()), special.size() - 1)];
  }
  BsdfParams material();
  glm::dvec3 direction();
  glm::dvec3 incoming(const glm::dvec3& wo, double alpha);

 private:
  std::mt19937 g_;
};

BsdfParams Points::material() {
  BsdfParams p;
  for (int c = 0; c < 3; ++c) p.baseColor[c] = pick({0.0f, 1.0f});
  p.metallic = pick({0.0f, 1.0f});
  p.roughness = pick({0.0f, 0.01f, 0.045f, 1.0f});  // 0 and 0.01: below the floor
  return p;
}

// A direction: uniform over the hemisphere, grazing (cos log-uniform in [1e-6, 1e-2]),
// the normal itself, or below the surface.
glm::dvec3 Points::direction() {
  const double kind = uniform(), phi = 2.0 * kRefPi * uniform();
  double c = uniform();
  if (kind < 0.3) c = std::pow(10.0, -6.0 + 4.0 * uniform());
  if (kind > 0.95) c = 1.0;
  if (kind > 0.9 && kind <= 0.95) c = -c;
  const double s = std::sqrt(1.0 - c * c);
  return {s * std::cos(phi), s * std::sin(phi), c};
}

// Half of the wi near the mirror direction, reflected about h drawn from the GGX lobe by
// its cdf tan^2 theta_h = alpha^2 xi / (1 - xi) (Walter et al. 2007, eq. 35): random wi
// alone would almost never land in the sharp highlight of roughness 0.045.
glm::dvec3 Points::incoming(const glm::dvec3& wo, double alpha) {
  if (uniform() < 0.5 || wo.z <= 0.0) return direction();
  const double xi = uniform(), phi = 2.0 * kRefPi * uniform();
  const double th = std::atan(alpha * std::sqrt(xi / (1.0 - xi)));
  const glm::dvec3 h(std::sin(th) * std::cos(phi), std::sin(th) * std::sin(phi), std::cos(th));
  const glm::dvec3 wi = 2.0 * glm::dot(wo, h) * h - wo;
  return wi.z > 0.0 ? wi : direction();
}

// The worst error over all points, in units of u (|ref| + S), and where it was.
struct Worst {
  double ulps = 0.0;
  std::string where;
  void add(double err, double bound, const std::function<std::string()>& describe) {
    const double inf = std::numeric_limits<double>::infinity();
    const double ulps1 = bound > 0.0 ? err / bound : (err > 0.0 ? inf : 0.0);
    if (ulps1 > ulps) ulps = ulps1, where = describe();
  }
};

struct PointwiseErrors {
  Worst diffuse, specular, total;
};

std::string describe(const BsdfParams& p, glm::vec3 wo, glm::vec3 wi, int c) {
  std::ostringstream s;
  s.precision(9);
  s << "base (" << p.baseColor.r << ", " << p.baseColor.g << ", " << p.baseColor.b << ") metallic "
    << p.metallic << " roughness " << p.roughness << " wo (" << wo.x << ", " << wo.y << ", " << wo.z
    << ") wi (" << wi.x << ", " << wi.y << ", " << wi.z << ") channel " << c;
  return s.str();
}

// One point: each lobe and evalBsdf's sum against the reference, per channel, in u.
// woD and wiD are float-representable: the renderer gets them exactly.
void comparePoint(const RendererLobes& renderer, const ReferenceLobes& reference,
                  const BsdfParams& p, const glm::dvec3& woD, const glm::dvec3& wiD,
                  PointwiseErrors& e) {
  const RefMaterial m = refOf(p);
  const glm::vec3 wo(woD), wi(wiD);
  const Lobes r = renderer(p, wo, wi), ref = reference(m, woD, wiD);
  const double sS = specularScale(m, woD, wiD);
  for (int c = 0; c < 3; ++c) {
    const auto where = [&] { return describe(p, wo, wi, c); };
    const double bS = kU * (std::abs(ref.specular[c]) + sS);
    const double bD = kU * (std::abs(ref.diffuse[c]) + diffuseScale(m, woD, wiD, c));
    e.specular.add(std::abs(r.specular[c] - ref.specular[c]), bS, where);
    e.diffuse.add(std::abs(r.diffuse[c] - ref.diffuse[c]), bD, where);
    // evalBsdf = the lobes' sum: their bounds, weighted as below, plus one addition.
    const double refT = ref.diffuse[c] + ref.specular[c];
    const double bT = (kSpecularUlps * bS + kDiffuseUlps * bD + kU * std::abs(refT)) /
                      kSpecularUlps;  // in the specular lobe's units
    e.total.add(std::abs(r.total[c] - refT), bT, where);
  }
}

PointwiseErrors comparePointwise(const RendererLobes& renderer, const ReferenceLobes& reference,
                                 int n) {
  Points pts(20260517u);
  PointwiseErrors e;
  for (int i = 0; i < n; ++i) {
    const BsdfParams p = pts.material();
    const glm::dvec3 wo = pts.direction();
    // Rounded to float once: the renderer and the reference see the same inputs.
    const glm::dvec3 woF = test::refToFloat(wo);
    const glm::dvec3 wiF = test::refToFloat(pts.incoming(woF, test::refAlpha(p.roughness)));
    comparePoint(renderer, reference, p, woF, wiF, e);
  }
  return e;
}

TEST(BsdfReference, LobesMatchTheThesisFormulasAtRandomPoints) {
  // 2 x 10^4 points: random materials with metallic and roughness often exactly 0 or 1
  // (or 0.045, or below the floor), wo and wi uniform, grazing down to cos = 1e-6, normal
  // or below the surface, half the wi in the specular highlight. Bounds: kSpecularUlps and
  // kDiffuseUlps above (first-order float rounding, ~2x margin); evalBsdf within the sum
  // of the two plus its one addition.
  const PointwiseErrors e = comparePointwise(rendererLobes, referenceLobes, 20000);
  EXPECT_LE(e.specular.ulps, kSpecularUlps) << e.specular.where;
  EXPECT_LE(e.diffuse.ulps, kDiffuseUlps) << e.diffuse.where;
  EXPECT_LE(e.total.ulps, kSpecularUlps) << e.total.where;
  RecordProperty("worst_specular_ulps", std::to_string(e.specular.ulps));
  RecordProperty("worst_diffuse_ulps", std::to_string(e.diffuse.ulps));
  RecordProperty("worst_total_ulps", std::to_string(e.total.ulps));
}

// --- 2. GGX normalisation. ----------------------------------------------------------------

// int D(h) (n.h) dwh over theta_h with s = ln(tan theta_h / alpha) in [s0, s1], dtheta =
// sin cos ds: 2 pi int D cos^2 sin^2 ds. In s a GGX lobe of any alpha is the same bump,
// tau^2 / (pi (1 + tau^2)^2) with tau = e^s, analytic in |Im s| < pi/2: composite
// Gauss-Legendre, panels of width 4 (rho = 2.06) of 24 nodes, error ~2.06^-48 ~ 1e-15.
// d: theta -> D.
template <class D>
double projectedArea(const D& d, double alpha, double s0, double s1) {
  const test::RefRule r = test::refCompositeGauss(24, s0, s1, 4.0);
  double sum = 0.0;
  for (size_t i = 0; i < r.x.size(); ++i) {
    const double th = std::atan(alpha * std::exp(r.x[i])), c = std::cos(th), s = std::sin(th);
    sum += r.w[i] * d(th) * c * c * s * s;
  }
  return 2.0 * kRefPi * sum;
}

// ggxD at theta_h, at an azimuth with both h.x and h.y non-zero (D is isotropic).
double rendererD(double theta, float alpha) {
  const glm::dvec3 h(std::sin(theta) * std::cos(1.0), std::sin(theta) * std::sin(1.0),
                     std::cos(theta));
  return ggxD(glm::vec3(h), alpha);
}

TEST(BsdfReference, GgxIsNormalisedAndHalfItsAreaLiesWithinTanThetaAlpha) {
  // Walter et al. 2007, eq. 4: int D (n.h) dwh = 1; and by GGX's cdf (their eq. 35, P =
  // tan^2 / (alpha^2 + tan^2)) half of it below tan theta_h = alpha, s = 0, which a
  // wrong width fails (a^2 -> a in D is GGX of alpha' = sqrt(alpha): still normalised).
  // Over s in [-18, 18] (or its halves): the cut tails hold e^-36 = 2e-16 each, the rule's
  // error is ~1e-15 (projectedArea). Renderer: D in float at float-rounded h, ~48 u plus
  // <= 4 u from the rounding of h (D's relative sensitivity to h.x, h.y is <= 4): 64 u =
  // 3.8e-6. Reference: double, but refGgxD's 1 - (n.h)^2 cancels near the peak, ~5e-11
  // at alpha = 0.045^2 (reference_bsdf.h): 1e-10.
  for (float alpha : {kMinAlpha, 0.25f, 1.0f}) {  // kMinAlpha = 0.045^2
    const double a = alpha;
    const auto ours = [&](double th) { return rendererD(th, alpha); };
    const auto ref = [&](double th) { return test::refGgxD(std::cos(th), a); };
    EXPECT_NEAR(projectedArea(ours, a, -18.0, 18.0), 1.0, 64.0 * kU) << alpha;
    EXPECT_NEAR(projectedArea(ours, a, -18.0, 0.0), 0.5, 64.0 * kU) << alpha;
    EXPECT_NEAR(projectedArea(ref, a, -18.0, 18.0), 1.0, 1e-10) << alpha;
    EXPECT_NEAR(projectedArea(ref, a, -18.0, 0.0), 0.5, 1e-10) << alpha;
  }
}

// --- 3. The projected area of the visible microsurface. ---------------------------------

// The rule over s = ln tan theta_h for int max(0, wo.h) D dwh: composite panels of width 4
// up to where wo's horizon wo.h = 0 enters the circle of azimuths (theta_h = pi/2 -
// theta_o), then the end-clustered rule, smooth across the horizon's (s - s1)^3/2. Above
// the horizon the integrand falls only as ~alpha^2 e^-s (max(0, wo.h) stays ~sin theta_o
// near theta_h = pi/2): cut at ln alpha + 40, e^-40 = 4e-18.
test::RefRule visibleRule(double thetaO, double alpha) {
  const double s0 = std::log(alpha) - 18.0, s2 = std::log(alpha) + 40.0;
  const double s1 = thetaO > 0.0 ? std::clamp(-std::log(std::tan(thetaO)), s0, s2) : s2;
  test::RefRule r = test::refCompositeGauss(24, s0, s1, 4.0);
  if (s2 > s1) r.append(test::refEndClusteredGauss(24, s1, s2, int(std::ceil((s2 - s1) / 4))));
  return r;
}

// int max(0, wo.h) D(h) dwh for wo in the xz-plane, phi between the horizon's crossings,
// cos phi > -cot theta_o cot theta_h (32 Gauss-Legendre nodes of a smooth cosine). d: h -> D.
template <class D>
double visibleProjection(const D& d, const glm::dvec3& wo, double alpha) {
  const double thetaO = std::atan2(wo.x, wo.z);
  const test::RefRule r = visibleRule(thetaO, alpha), unit = test::refGaussLegendre(32, -1, 1);
  double sum = 0.0;
  for (size_t i = 0; i < r.x.size(); ++i) {
    const double th = std::atan(std::exp(r.x[i])), st = std::sin(th), ct = std::cos(th);
    const double cut = thetaO > 0.0 ? -std::cos(thetaO) * ct / (std::sin(thetaO) * st) : -1.0;
    const double phiMax = std::acos(std::clamp(cut, -1.0, 1.0));
    for (size_t j = 0; j < unit.x.size(); ++j) {
      const double phi = phiMax * unit.x[j];
      const glm::dvec3 h(st * std::cos(phi), st * std::sin(phi), ct);
      const double w = r.w[i] * phiMax * unit.w[j] * st * st * ct;  // dwh = sin dtheta dphi
      sum += w * std::max(0.0, glm::dot(wo, h)) * d(h);
    }
  }
  return sum;
}

TEST(BsdfReference, SmithG1ProjectsTheVisibleMicrosurfaceOntoWo) {
  // Heitz 2014 ("Understanding the Masking-Shadowing Function", JCGT 3(2)): the visible
  // microsurface projects onto wo as the macro-surface does, int G1(wo, h) max(0, wo.h)
  // D(h) dwh = wo.z; the separable Smith G1(wo, h) = G1(wo) for wo.h > 0 comes out of the
  // integral. The renderer's ggxG1 and ggxD (float, at float-rounded wo and h; the
  // geometry in double), and the reference's at the exact unit wo (a float-rounded wo is
  // off unit length by ~u, which the identity, linear in |wo|, would show). The rule's
  // error is below the reference's 1e-11 agreement in every case. Renderer: D ~64 u as
  // above plus G1 ~8 u: 96 u = 5.7e-6 relative. Reference: refGgxD's cancellation as
  // above, 1e-10 relative.
  for (float alpha : {kMinAlpha, 0.05f, 0.25f, 1.0f})
    for (double theta : {0.0, 30.0, 60.0, 80.0, 89.0, 89.9}) {
      const glm::dvec3 wo = incident(theta), exact = incident(theta, test::RefNodes::Exact);
      const double a = alpha;
      const auto ourD = [&](const glm::dvec3& h) { return double(ggxD(glm::vec3(h), alpha)); };
      const auto refD = [&](const glm::dvec3& h) { return test::refGgxD(h.z, a); };
      const double ours = ggxG1(glm::vec3(wo), alpha) * visibleProjection(ourD, wo, a);
      const double ref = test::refSmithG1(exact.z, a) * visibleProjection(refD, exact, a);
      EXPECT_NEAR(ours, wo.z, 96.0 * kU * wo.z) << "alpha " << alpha << " theta " << theta;
      EXPECT_NEAR(ref, exact.z, 1e-10 * exact.z) << "alpha " << alpha << " theta " << theta;
    }
}

// --- 4. Directional albedo of each lobe. --------------------------------------------------

using Lobe = std::function<glm::dvec3(const glm::dvec3&, const glm::dvec3&)>;

// A lobe of the renderer, at float-representable directions (the rules below round).
Lobe rendererLobe(const BsdfParams& p, bool specular) {
  return [p, specular](const glm::dvec3& wo, const glm::dvec3& wi) {
    const BsdfLobes f = evalBsdfLobes(p, glm::vec3(wo), glm::vec3(wi));
    return glm::dvec3(specular ? f.specular : f.diffuse);
  };
}

// int f cos dwi over wi by Gauss-Legendre in cos theta_i (nCos a panel, 4 panels) and phi
// (nPhi a panel, 8 panels), nodes rounded to float or not as refAlbedoHalfVector's.
glm::dvec3 directAlbedo(const Lobe& f, const glm::dvec3& wo, int nCos, int nPhi,
                        test::RefNodes nodes = test::RefNodes::Float) {
  const test::RefRule rc = test::refCompositeGauss(nCos, 0.0, 1.0, 0.25);
  const test::RefRule rp = test::refCompositeGauss(nPhi, 0.0, 2.0 * kRefPi, 0.25 * kRefPi);
  glm::dvec3 sum(0.0);
  for (size_t i = 0; i < rc.x.size(); ++i)
    for (size_t j = 0; j < rp.x.size(); ++j) {
      const double c = rc.x[i], s = std::sqrt(1.0 - c * c);
      const glm::dvec3 wi = test::refNode({s * std::cos(rp.x[j]), s * std::sin(rp.x[j]), c}, nodes);
      sum += f(wo, wi) * (wi.z * rc.w[i] * rp.w[j]);
    }
  return sum;
}

// The diffuse lobe depends on wi through cos theta_i alone, as a polynomial of degree 5:
// 4 panels x 4 nodes integrate its albedo (degree 6 with the cosine) exactly; 2 x 8 in phi.
glm::dvec3 diffuseAlbedo(const Lobe& f, const glm::dvec3& wo) {
  return directAlbedo(f, wo, 4, 2);
}

// Over half-vectors (refAlbedoHalfVector): 24 nodes a panel in s (panels of width 2 are
// well inside GGX's strip of analyticity) x 48 in phi.
glm::dvec3 specularAlbedo(const Lobe& f, const glm::dvec3& wo, double roughness) {
  return test::refAlbedoHalfVector(f, wo, test::refAlpha(roughness), 24, 48);
}

struct AlbedoCase {
  BsdfParams p;
  double theta;
  std::string describe() const {
    return "roughness " + std::to_string(p.roughness) + " metallic " + std::to_string(p.metallic) +
           " theta " + std::to_string(theta);
  }
};

std::vector<AlbedoCase> albedoCases() {
  std::vector<AlbedoCase> cases;
  for (float roughness : {0.045f, 0.5f, 1.0f})
    for (float metallic : {0.0f, 1.0f})
      for (double theta : {0.0, 45.0, 80.0, 89.0})
        cases.push_back({{glm::vec3(0.9f, 0.6f, 0.2f), metallic, roughness}, theta});
  return cases;
}

Lobe referenceSpecular(const RefMaterial& m) {
  return [m](const glm::dvec3& wo, const glm::dvec3& wi) { return test::refSpecular(m, wo, wi); };
}
Lobe referenceDiffuse(const RefMaterial& m) {
  return [m](const glm::dvec3& wo, const glm::dvec3& wi) { return test::refDiffuse(m, wo, wi); };
}
Lobe fresnelFreeSpecular(const RefMaterial& m) {  // specularScale as a lobe
  return [m](const glm::dvec3& wo, const glm::dvec3& wi) {
    return glm::dvec3(specularScale(m, wo, wi));
  };
}

TEST(BsdfReference, LobeAlbedosMatchTheReferenceByQuadrature) {
  // The albedo of each lobe, int f cos dwi, from evalBsdfLobes and from the reference by
  // the same rule at the same float nodes (the specular lobe over half-vectors, resolving
  // roughness 0.045's highlight; the diffuse lobe over wi), so the rules' own errors cancel
  // and float rounding remains: the pointwise bounds integrated, k u (A_ref + A_S) with A_S
  // the albedo of the Fresnel-free lobe (S of the bounds).
  for (const AlbedoCase& k : albedoCases()) {
    const RefMaterial m = refOf(k.p);
    const glm::dvec3 wo = incident(k.theta);
    const glm::dvec3 oursS = specularAlbedo(rendererLobe(k.p, true), wo, m.roughness);
    const glm::dvec3 wantS = specularAlbedo(referenceSpecular(m), wo, m.roughness);
    const double scaleS = specularAlbedo(fresnelFreeSpecular(m), wo, m.roughness).r;
    const glm::dvec3 oursD = diffuseAlbedo(rendererLobe(k.p, false), wo);
    const glm::dvec3 wantD = diffuseAlbedo(referenceDiffuse(m), wo);
    for (int c = 0; c < 3; ++c) {
      const double scaleD = (1.0 - m.metallic) * m.baseColor[c];  // int cos / pi dwi = 1
      EXPECT_NEAR(oursS[c], wantS[c], kSpecularUlps * kU * (wantS[c] + scaleS))
          << "specular, " << k.describe() << " channel " << c;
      EXPECT_NEAR(oursD[c], wantD[c], kDiffuseUlps * kU * (wantD[c] + scaleD))
          << "diffuse, " << k.describe() << " channel " << c;
    }
  }
}

TEST(BsdfReference, AlbedoQuadraturesAgreeWithIndependentAnswers) {
  // The rules above, at exact nodes and an exact wo, against answers they do not share.
  // Diffuse: the reference lobe's albedo is (1 - F(n.wo)) (1 - m) base (1 - F0) 20/21, as
  // int 2 (1 - F(c)) c dc = (1 - F0) (1 - 2 B(2, 6)) = (1 - F0) 20/21; the rule is exact
  // for this polynomial: 1e-12 relative.
  // Specular, rough lobes: over half-vectors against directly over wi (64 x 48 nodes a
  // panel), which converges slowest at 89 degrees, where the back-scatter corner (wi near
  // -wo, h swinging round over ~wo.z) needs them: < 5e-9 there. Roughness 0.045, which
  // only half-vectors resolve: against the same rule with twice the phi nodes, < 5e-9 at
  // 80-89 degrees (the horizon's boundary layer, where G1(wi) rises over cos ~alpha).
  // 2e-8 absolute for both (albedos <= 1).
  const auto exact = test::RefNodes::Exact;
  for (const AlbedoCase& k : albedoCases()) {
    const RefMaterial m = refOf(k.p);
    const glm::dvec3 wo = incident(k.theta, exact);
    const glm::dvec3 f0 = glm::mix(glm::dvec3(0.04), m.baseColor, m.metallic), one(1.0);
    const glm::dvec3 closed = (one - test::refSchlick(f0, wo.z)) * (1.0 - m.metallic) *
                              m.baseColor * (one - f0) * (20.0 / 21.0);
    const glm::dvec3 d = directAlbedo(referenceDiffuse(m), wo, 4, 2, exact);
    const Lobe spec = referenceSpecular(m);
    const double alpha = test::refAlpha(m.roughness);
    const glm::dvec3 half = test::refAlbedoHalfVector(spec, wo, alpha, 24, 48, exact);
    const glm::dvec3 check = m.roughness >= 0.5
                                 ? directAlbedo(spec, wo, 64, 48, exact)
                                 : test::refAlbedoHalfVector(spec, wo, alpha, 24, 96, exact);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(d[c], closed[c], 1e-12 * closed[c]) << k.describe() << " channel " << c;
      EXPECT_NEAR(half[c], check[c], 2e-8) << k.describe() << " channel " << c;
    }
  }
}

}  // namespace
}  // namespace photovr
