// The glass lobe of trace/bsdf.h (KHR_materials_transmission) and the dielectric layer of
// KHR_materials_ior / KHR_materials_specular: sampling against the pdf, value against an
// independent reference, generalised reciprocity, energy, and closed forms.
#include <cfloat>
#include <cmath>

#include <gtest/gtest.h>

#include "tests/trace/chi_square.h"
#include "tests/trace/reference_glass.h"
#include "trace/bsdf.h"
#include "trace/rng.h"
#include "trace/sampling.h"

namespace photovr {
namespace {

using test::chiSquareTest;
using test::Histogram;

constexpr int kSamples = 200000;  // ~250 per cell of the 20 x 40 grid

Sampler testSampler(uint32_t seed) {
  return Sampler::make({.pixel = seed, .seed = 4242u});
}

glm::vec3 incident(float thetaDegrees) {
  const float t = glm::radians(thetaDegrees);
  return {std::sin(t), 0.0f, std::cos(t)};
}

BsdfParams glass(float roughness, float eta, bool thin = false, float transmission = 1.0f,
                 glm::vec3 tint = glm::vec3(1.0f), float metallic = 0.0f) {
  BsdfParams p{tint, metallic, roughness};
  p.transmission = transmission;
  p.eta = eta;
  p.thinWalled = thin;
  return p;
}

test::RefGlass refOf(const BsdfParams& p) {
  return {glm::dvec3(p.baseColor), p.roughness, p.eta, p.thinWalled};
}

// The whole sphere: x = (cos theta + 1) / 2, y = phi / (2 pi); dw = 4 pi dx dy.
glm::vec2 sphereCoords(const glm::vec3& w) {
  float phi = std::atan2(w.y, w.x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  return {std::clamp(0.5f * (w.z + 1.0f), 0.0f, 1.0f), phi * kInv2Pi};
}

glm::vec3 sphereDirection(double x, double y) {
  const double z = 2.0 * x - 1.0, r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return glm::vec3(float(r * std::cos(2 * M_PI * y)), float(r * std::sin(2 * M_PI * y)), float(z));
}

struct GlassCase {
  float roughness, eta, theta;
  bool thin;
  float transmission = 1.0f, metallic = 0.0f;
};
void PrintTo(const GlassCase& c, std::ostream* os) {
  *os << "roughness " << c.roughness << " eta " << c.eta << " theta " << c.theta
      << (c.thin ? " thin" : "") << " transmission " << c.transmission << " metallic "
      << c.metallic;
}

class GlassChiSquare : public testing::TestWithParam<GlassCase> {};

TEST_P(GlassChiSquare, SampledDirectionsFollowPdfOverTheSphere) {
  const GlassCase c = GetParam();
  const BsdfParams p =
      glass(c.roughness, c.eta, c.thin, c.transmission, glm::vec3(0.8f), c.metallic);
  const glm::vec3 wo = incident(c.theta);
  Histogram hist(20, 40);
  Sampler s = testSampler(uint32_t(c.theta * 7 + c.roughness * 100));
  for (int i = 0; i < kSamples; ++i) {
    const BsdfSample b = sampleBsdf(p, wo, s.next2());
    if (b.valid())
      hist.add(sphereCoords(b.wi));
    else
      hist.addFailure();
  }
  const auto r = chiSquareTest(
      hist, [&](double x, double y) { return 4.0 * M_PI * pdfBsdf(p, wo, sphereDirection(x, y)); });
  EXPECT_TRUE(r.passed()) << r.describe();
}

// Rough lobes the 20 x 40 sphere grid resolves: entering and leaving a medium (60 degrees
// inside is beyond the critical angle of 41.8 degrees), a thin wall, grazing, and mixtures
// with the BRDF (partial transmission, a partly metallic glass).
INSTANTIATE_TEST_SUITE_P(
    RoughnessEtaAngle, GlassChiSquare,
    testing::Values(GlassCase{0.5f, 1.5f, 30.0f, false}, GlassCase{0.5f, 1.0f / 1.5f, 30.0f, false},
                    GlassCase{0.5f, 1.0f / 1.5f, 60.0f, false}, GlassCase{0.3f, 1.5f, 70.0f, false},
                    GlassCase{0.6f, 1.5f, 45.0f, true}, GlassCase{1.0f, 1.33f, 80.0f, false},
                    GlassCase{0.5f, 1.5f, 40.0f, false, 0.6f, 0.0f},
                    GlassCase{0.5f, 1.0f / 1.5f, 20.0f, false, 1.0f, 0.3f}));

TEST(Glass, ValueMatchesTheIndependentReference) {
  // Random rough and sharp glass, both sides, both walls. Tolerance: float rounding of the
  // same closed forms, 2e-4 relative, plus 3e-6 absolute for the transmission just below
  // the critical angle, where 1 - F ~ sqrt(cos - cos_c) turns the float error of wo.h into
  // a large relative error of a small value (seen: 1.7 % of 6e-5).
  Sampler s = testSampler(3);
  int compared = 0;
  for (int i = 0; i < 20000; ++i) {
    const float eta = s.next() < 0.5f ? 1.0f + 1.5f * s.next() : 1.0f / (1.0f + 1.5f * s.next());
    const bool thin = s.next() < 0.3f;
    const BsdfParams p = glass(0.1f + 0.9f * s.next(), thin ? std::max(eta, 1.0f / eta) : eta, thin,
                               1.0f, glm::vec3(s.next(), s.next(), s.next()));
    const glm::vec3 wo = sampleCosineHemisphere(s.next2());
    const glm::vec3 wi = sampleUniformSphere(s.next2());
    const glm::dvec3 want = test::refGlass(refOf(p), glm::dvec3(wo), glm::dvec3(wi));
    const glm::vec3 got = evalBsdf(p, wo, wi);
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(got[k], want[k], 2e-4 * want[k] + 3e-6)
          << i << " eta " << p.eta << (thin ? " thin" : "") << " wi.z " << wi.z;
    compared += want.x > 0.0;
  }
  EXPECT_GT(compared, 10000);  // most pairs are not zero
}

TEST(Glass, FresnelMatchesTheEquationsInAngles) {
  for (float eta : {1.0f / 2.4f, 1.0f / 1.5f, 1.0f / 1.01f, 1.0f, 1.33f, 1.5f, 2.4f})
    for (float c = 0.0f; c <= 1.0f; c += 1.0f / 64.0f) {
      const double want = test::refFresnelAngles(c, 1.0, eta);
      ASSERT_NEAR(fresnelDielectric(c, eta), want, 2e-5 + 1e-5 * want) << eta << " " << c;
    }
  EXPECT_EQ(fresnelDielectric(0.3f, 1.0f / 1.5f), 1.0f);  // beyond the critical angle
}

// 4 eps / (2 (c - c_crit)): the relative float error of a refraction's value from a to b
// (b through the surface, eta = n_b / n_a > 1), whose 1 - F goes as sqrt(c - c_crit) in
// c = |b.h| near the critical angle of the dense side (Walter et al. 2007's half-vector).
float criticalConditioning(const glm::vec3& a, const glm::vec3& b, float eta) {
  const glm::vec3 h = glm::normalize(a + eta * b);
  const float c = std::abs(glm::dot(b, h)), cCritical = std::sqrt(1.0f - 1.0f / (eta * eta));
  return 2.0f * FLT_EPSILON / std::max(c - cCritical, FLT_EPSILON);
}

TEST(Glass, GeneralisedReciprocityAcrossTheInterface) {
  // Radiance BTDFs are not symmetric across a refracting interface (Veach 1997, sec. 5.2):
  // f(wo, wi) / n_wo^2 = f(wi, wo) / n_wi^2, so with eta = n_wi / n_wo, f(wo, wi) = f(wi,
  // wo) / eta^2, the latter evaluated from the other side (1 / eta, the frame flipped so
  // its wo is up). Thin walls and reflection are plainly reciprocal. 1e-4 relative: float
  // rounding of two half-vectors; 3e-6 absolute near the critical angle (as above); and
  // closer to it, where 1 - F goes as sqrt(c - c_crit) with c = |b.h| on the dense side, a
  // float error of ~4 eps in c moves the value by 4 eps / (2 (c - c_crit)) relative (seen:
  // 2.8 % at c - c_crit = 2.3e-6).
  Sampler s = testSampler(5);
  for (int i = 0; i < 5000; ++i) {
    const float eta = 1.0f + s.next();
    const glm::vec3 a = sampleCosineHemisphere(s.next2());
    const glm::vec3 b = -sampleCosineHemisphere(s.next2());  // through the surface
    const glm::vec3 flipA = -a, flipB = -b;                  // the other side's frame: z up
    for (bool thin : {false, true}) {
      const BsdfParams front = glass(0.4f, eta, thin),
                       back = glass(0.4f, thin ? eta : 1 / eta, thin);
      const float there = evalBsdf(front, a, b).r, back_ = evalBsdf(back, flipB, flipA).r;
      const float scale = thin ? 1.0f : 1.0f / (eta * eta);
      const float critical = thin ? 0.0f : criticalConditioning(a, b, eta);
      ASSERT_NEAR(there, scale * back_, (1e-4f + critical) * there + 3e-6f)
          << i << (thin ? " thin" : "");
    }
    const glm::vec3 c = sampleCosineHemisphere(s.next2());
    const BsdfParams p = glass(0.4f, eta);
    ASSERT_NEAR(evalBsdf(p, a, c).r, evalBsdf(p, c, a).r, 1e-5f * evalBsdf(p, a, c).r + 1e-8f);
  }
}

struct Estimate {
  double mean = 0.0, sigma = 0.0;
};

// Mean of f |cos| / pdf over sampled directions, the reflected and transmitted halves.
void glassHalves(const BsdfParams& p, const glm::vec3& wo, int n, Estimate& reflected,
                 Estimate& transmitted) {
  Sampler s = testSampler(9);
  double sr = 0, sr2 = 0, st = 0, st2 = 0;
  for (int i = 0; i < n; ++i) {
    const BsdfSample b = sampleBsdf(p, wo, s.next2());
    const double w = b.weight.g;
    (b.wi.z > 0.0f ? sr : st) += w;
    (b.wi.z > 0.0f ? sr2 : st2) += w * w;
  }
  auto fill = [n](Estimate& e, double sum, double sum2) {
    e.mean = sum / n;
    e.sigma = std::sqrt(std::max(0.0, sum2 / n - e.mean * e.mean) / n);
  };
  fill(reflected, sr, sr2);
  fill(transmitted, st, st2);
}

TEST(Glass, SmoothInterfaceSplitsByFresnelAndScalesRadianceByOneOverEtaSquared) {
  // Roughness 0 (alpha 0.045^2: lobes ~0.1 degree wide): reflection carries F(theta),
  // refraction (1 - F) / eta^2 (radiance compressed into the smaller solid angle), a thin
  // wall 1 - F unscaled. Tolerance: 4 standard errors plus 2e-3 for the spread of F over
  // the narrow lobe and its single-scattering loss.
  for (float theta : {0.0f, 30.0f, 60.0f, 80.0f})
    for (float eta : {1.5f, 1.0f / 1.5f})
      for (bool thin : {false, true}) {
        if (thin && eta < 1.0f) continue;
        const BsdfParams p = glass(0.0f, eta, thin);
        const glm::vec3 wo = incident(theta);
        const double f = test::refFresnelAngles(wo.z, 1.0, eta);
        Estimate r, t;
        glassHalves(p, wo, 40000, r, t);
        const double tWant = thin ? 1.0 - f : (1.0 - f) / (eta * eta);
        EXPECT_NEAR(r.mean, f, 4 * r.sigma + 2e-3) << theta << " eta " << eta << thin;
        EXPECT_NEAR(t.mean, tWant, 4 * t.sigma + 2e-3) << theta << " eta " << eta << thin;
      }
}

TEST(Glass, RoughGlassConservesEnergy) {
  // Reflection plus transmission scaled back by eta^2 (the radiance the BTDF compressed):
  // at most 1, the single-scattering microfacet loss below (up to ~65 % for alpha 1 at
  // grazing angles: no multiple scattering). 3 standard errors + 1e-3. At roughness 0.2
  // (alpha 0.04) the loss is a few percent: at least 0.9 there, or a half is lost.
  for (float roughness : {0.2f, 0.5f, 1.0f})
    for (float eta : {1.5f, 1.0f / 1.5f, 2.4f})
      for (float theta : {0.0f, 45.0f, 85.0f}) {
        Estimate r, t;
        glassHalves(glass(roughness, eta), incident(theta), 20000, r, t);
        const double total = r.mean + t.mean * eta * eta;
        const double sigma = std::hypot(r.sigma, t.sigma * eta * eta);
        EXPECT_LE(total, 1.0 + 3 * sigma + 1e-3) << roughness << " " << eta << " " << theta;
        if (roughness <= 0.2f) {
          EXPECT_GE(total, 0.9) << roughness << " " << eta << " " << theta;
        }
      }
}

TEST(Glass, ZeroTransmissionIsTheBrdfToTheBit) {
  // transmission 0 leaves the metallic-roughness BRDF exactly as before: no golden image
  // moves for scenes without the extension.
  Sampler s = testSampler(21);
  for (int i = 0; i < 2000; ++i) {
    const BsdfParams a{glm::vec3(s.next(), s.next(), s.next()), s.next(), s.next()};
    BsdfParams b = a;
    b.eta = 1.33f;
    b.thinWalled = false;
    const glm::vec3 wo = sampleCosineHemisphere(s.next2()), wi = sampleUniformSphere(s.next2());
    ASSERT_EQ(evalBsdf(a, wo, wi), evalBsdf(b, wo, wi));
    const glm::vec2 u = s.next2();
    ASSERT_EQ(sampleBsdf(a, wo, u).weight, sampleBsdf(b, wo, u).weight);
  }
}

TEST(DielectricLayer, SpecularZeroIsPureLambert) {
  // KHR_materials_specular 0 (f0 = f90 = 0): no specular lobe, the diffuse lobe undimmed.
  BsdfParams p{glm::vec3(0.7f, 0.5f, 0.3f), 0.0f, 0.5f};
  p.dielectricF0 = glm::vec3(0.0f);
  p.dielectricF90 = 0.0f;
  Sampler s = testSampler(23);
  for (int i = 0; i < 1000; ++i) {
    const glm::vec3 wo = sampleCosineHemisphere(s.next2()), wi = sampleCosineHemisphere(s.next2());
    const BsdfLobes f = evalBsdfLobes(p, wo, wi);
    ASSERT_EQ(f.specular, glm::vec3(0.0f));
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(f.diffuse[k], p.baseColor[k] / kPi, 1e-7f);
  }
  EXPECT_EQ(specularProbability(p, incident(40.0f)), 0.0f);
}

TEST(DielectricLayer, IorAndSpecularColourSetTheFresnel) {
  // The specular lobe's value is linear in Schlick's F = f0 + (f90 - f0)(1 - v.h)^5: with
  // the base dark (no diffuse), f(ior 1.33) / f(ior 1.5) at normal incidence is
  // f0(1.33) / f0(1.5) = 0.02006 / 0.04, and a specular colour scales f0 per channel.
  const glm::vec3 wo(0, 0, 1), wi(0, 0, 1);
  BsdfParams a{glm::vec3(0.0f), 0.0f, 0.3f}, b = a;
  const double f0Water = std::pow(0.33 / 2.33, 2.0);
  b.dielectricF0 = glm::vec3(float(f0Water)) * glm::vec3(1.0f, 0.5f, 0.25f);
  const glm::vec3 fa = evalBsdf(a, wo, wi), fb = evalBsdf(b, wo, wi);
  EXPECT_NEAR(fb.r / fa.r, f0Water / 0.04, 1e-5);
  EXPECT_NEAR(fb.g / fa.r, 0.5 * f0Water / 0.04, 1e-5);
  EXPECT_NEAR(fb.b / fa.r, 0.25 * f0Water / 0.04, 1e-5);
}

TEST(Glass, FiniteForEdgeInputs) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (float eta : {0.0f, 1e-9f, 1.0f, 1.5f, 1e9f, nan, -1.0f})
    for (float r : {0.0f, 1.0f, nan})
      for (float t : {0.0f, 0.5f, 1.0f, nan})
        for (bool thin : {false, true}) {
          const BsdfParams p = glass(r, eta, thin, t);
          for (glm::vec3 wo :
               {glm::vec3(0, 0, 1), incident(89.99f), glm::vec3(1, 0, 0), glm::vec3(0, 0, -1)})
            for (glm::vec3 wi :
                 {glm::vec3(0, 0, -1), glm::vec3(0, 0, 1), -incident(89.99f), glm::vec3(1, 0, 0)}) {
              const BsdfEval e = evalBsdfAndPdf(prepareBsdf(p, wo), wi);
              ASSERT_TRUE(isFinite(e.f.total()) && std::isfinite(e.pdf)) << eta << " " << r;
              for (glm::vec2 u : {glm::vec2(0.0f), glm::vec2(kOneMinusEpsilon), glm::vec2(0.5f)}) {
                const BsdfSample b = sampleBsdf(p, wo, u);
                ASSERT_TRUE(isFinite(b.weight) && std::isfinite(b.pdf)) << eta << " " << r;
              }
            }
        }
}

}  // namespace
}  // namespace photovr
