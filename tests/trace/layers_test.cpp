// The sheen (KHR_materials_sheen) and clear-coat (KHR_materials_clearcoat) layers of
// trace/bsdf.h: sampling against the pdf, the value against an independent reference,
// reciprocity, energy, the coat's Fresnel over a black base, and the sheen albedo table.
#include <cmath>

#include <gtest/gtest.h>

#include "tests/trace/chi_square.h"
#include "tests/trace/reference_layers.h"
#include "trace/bsdf.h"
#include "trace/rng.h"
#include "trace/sampling.h"

namespace photovr {
namespace {

using test::chiSquareTest;
using test::Histogram;

Sampler testSampler(uint32_t seed) {
  return Sampler::make({.pixel = seed, .seed = 777u});
}

glm::vec3 incident(float thetaDegrees) {
  const float t = glm::radians(thetaDegrees);
  return {std::sin(t), 0.0f, std::cos(t)};
}

struct LayerCase {
  float theta;
  float coat, coatRoughness;
  float sheen, sheenRoughness;
  float roughness = 0.7f, transmission = 0.0f, metallic = 0.0f;
  float coatTilt = 0.0f;  // degrees between the coat's normal and the base's
};

// A unit normal 'degrees' away from +z, towards azimuth 30 degrees (off the plane of
// incidence, so a tilt breaks the lobes' mirror symmetry).
glm::vec3 tilted(float degrees) {
  const float t = glm::radians(degrees), phi = glm::radians(30.0f);
  return {std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi), std::cos(t)};
}
void PrintTo(const LayerCase& c, std::ostream* os) {
  *os << "theta " << c.theta << " coat " << c.coat << "/" << c.coatRoughness << " sheen " << c.sheen
      << "/" << c.sheenRoughness << " roughness " << c.roughness << " transmission "
      << c.transmission << " metallic " << c.metallic << " coat tilt " << c.coatTilt;
}

BsdfParams layered(const LayerCase& c, glm::vec3 base = glm::vec3(0.7f, 0.5f, 0.3f)) {
  BsdfParams p{base, c.metallic, c.roughness};
  p.clearcoat = c.coat;
  p.clearcoatRoughness = c.coatRoughness;
  p.coatNormal = tilted(c.coatTilt);
  p.sheenColor = glm::vec3(c.sheen, 0.8f * c.sheen, 0.6f * c.sheen);
  p.sheenRoughness = c.sheenRoughness;
  p.transmission = c.transmission;
  p.eta = 1.5f;
  p.thinWalled = false;
  return p;
}

// The whole sphere: x = (cos theta + 1) / 2, y = phi / (2 pi); dw = 4 pi dx dy (the glass
// lobe can send wi below the surface).
glm::vec2 sphereCoords(const glm::vec3& w) {
  float phi = std::atan2(w.y, w.x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  return {std::clamp(0.5f * (w.z + 1.0f), 0.0f, 1.0f), phi * kInv2Pi};
}

glm::vec3 sphereDirection(double x, double y) {
  const double z = 2.0 * x - 1.0, r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return glm::vec3(float(r * std::cos(2 * M_PI * y)), float(r * std::sin(2 * M_PI * y)), float(z));
}

class LayerChiSquare : public testing::TestWithParam<LayerCase> {};

TEST_P(LayerChiSquare, SampledDirectionsFollowPdfOverTheSphere) {
  const LayerCase c = GetParam();
  const BsdfParams p = layered(c);
  const glm::vec3 wo = incident(c.theta);
  Histogram hist(20, 40);
  Sampler s = testSampler(uint32_t(c.theta * 3 + c.coat * 50 + c.sheen * 70));
  for (int i = 0; i < 200000; ++i) {  // ~250 per cell
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

// Lobes the 20 x 40 grid resolves: a coat over a rough dielectric and over a metal, sheen
// alone (and at roughness 0, where the albedo normalisation acts), all three over glass.
INSTANTIATE_TEST_SUITE_P(
    CoatSheenBase, LayerChiSquare,
    testing::Values(LayerCase{30.0f, 1.0f, 0.4f, 0.0f, 0.0f},
                    LayerCase{70.0f, 0.6f, 0.5f, 0.0f, 0.0f, 0.5f, 0.0f, 1.0f},
                    LayerCase{45.0f, 0.0f, 0.0f, 0.9f, 0.5f},
                    LayerCase{80.0f, 0.0f, 0.0f, 1.0f, 0.0f},
                    LayerCase{40.0f, 1.0f, 0.5f, 0.8f, 0.6f, 0.5f, 1.0f, 0.0f},
                    // the coat about a normal of its own (its normal map)
                    LayerCase{30.0f, 1.0f, 0.3f, 0.0f, 0.0f, 0.7f, 0.0f, 0.0f, 25.0f},
                    LayerCase{60.0f, 0.8f, 0.4f, 0.5f, 0.5f, 0.5f, 0.0f, 1.0f, 40.0f}));

double tableAlbedo(double cosTheta, double sheenRoughness) {
  return sheenAlbedo(float(cosTheta), float(sheenRoughness));
}

TEST(Layers, ValueMatchesTheIndependentReference) {
  // Random coats, sheens and bases. Tolerance: float rounding of the same closed forms,
  // 3e-4 relative (Lambda's exp of a ~20-large fit amplifies the float error of its
  // argument) plus 1e-6 absolute.
  Sampler s = testSampler(3);
  for (int i = 0; i < 20000; ++i) {
    test::RefLayers m;
    m.base = {glm::dvec3(s.next(), s.next(), s.next()), s.next(), s.next()};
    m.sheenColor = s.next() < 0.3 ? glm::dvec3(0.0) : glm::dvec3(s.next(), s.next(), s.next());
    m.sheenRoughness = s.next();
    m.coat = s.next() < 0.3 ? 0.0 : s.next();
    m.coatRoughness = 0.1 + 0.9 * s.next();
    // Half the coats about a normal of their own, up to 40 degrees off the base's.
    const float tilt = s.next() < 0.5f ? 0.0f : 40.0f * s.next();
    m.coatNormal = glm::dvec3(tilted(tilt));
    BsdfParams p{glm::vec3(m.base.baseColor), float(m.base.metallic), float(m.base.roughness)};
    p.sheenColor = glm::vec3(m.sheenColor);
    p.sheenRoughness = float(m.sheenRoughness);
    p.clearcoat = float(m.coat);
    p.clearcoatRoughness = float(m.coatRoughness);
    p.coatNormal = tilted(tilt);
    const glm::vec3 wo = sampleCosineHemisphere(s.next2());
    const glm::vec3 wi = sampleCosineHemisphere(s.next2());
    const glm::dvec3 want = test::refLayered(m, tableAlbedo, glm::dvec3(wo), glm::dvec3(wi));
    const glm::vec3 got = evalBsdf(p, wo, wi);
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(got[k], want[k], 3e-4 * want[k] + 1e-6)
          << i << " wo.z " << wo.z << " wi.z " << wi.z;
  }
}

TEST(Layers, Reciprocal) {
  // Both layers' filters are symmetric in wo and wi (bsdf.h, "The layers"). 1e-5 relative:
  // float rounding, the half-vector computed from either side.
  Sampler s = testSampler(5);
  for (int i = 0; i < 5000; ++i) {
    const LayerCase c{0.0f,     s.next(), s.next(), s.next(),        s.next(),
                      s.next(), 0.0f,     s.next(), 40.0f * s.next()};
    const BsdfParams p = layered(c, glm::vec3(s.next(), s.next(), s.next()));
    const glm::vec3 a = sampleCosineHemisphere(s.next2()), b = sampleCosineHemisphere(s.next2());
    const glm::vec3 ab = evalBsdf(p, a, b), ba = evalBsdf(p, b, a);
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(ab[k], ba[k], 1e-5f * ab[k] + 1e-9f) << i;
  }
}

struct Estimate {
  double mean = 0.0, sigma = 0.0;
};

// The directional albedo by the BSDF's own sampler: the mean of f |cos| / pdf (green).
Estimate albedo(const BsdfParams& p, const glm::vec3& wo, int n, uint32_t seed) {
  Sampler s = testSampler(seed);
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double w = sampleBsdf(p, wo, s.next2()).weight.g;
    sum += w;
    sum2 += w * w;
  }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

TEST(Layers, EnergyDirectionalAlbedoAtMostOne) {
  // White everything: base, sheen and coat, at every sheen roughness including 0, where
  // the Charlie fit alone reflects up to 4x what arrives at grazing angles (bsdf.h). At most
  // 1 within 4 standard errors + 1e-3.
  for (float sheenRoughness : {0.0f, 0.2f, 0.5f, 1.0f})
    for (float coat : {0.0f, 1.0f})
      for (float theta : {0.0f, 45.0f, 75.0f, 85.0f, 89.5f}) {
        const LayerCase c{theta, coat, 0.3f, 1.0f, sheenRoughness, 0.5f};
        BsdfParams p = layered(c, glm::vec3(1.0f));
        p.sheenColor = glm::vec3(1.0f);
        const Estimate e = albedo(p, incident(theta), 40000, uint32_t(theta + 10 * coat));
        EXPECT_LE(e.mean, 1.0 + 4 * e.sigma + 1e-3)
            << "sheen roughness " << sheenRoughness << " coat " << coat << " theta " << theta;
      }
}

TEST(Layers, SmoothCoatOverBlackReflectsTheCoatsFresnel) {
  // A black base with no dielectric specular (KHR_materials_specular 0) under a smooth coat
  // of strength c: all that comes back is the coat's c F(theta), F Schlick with f0 0.04.
  // Tolerance: 4 standard errors + 2e-3 (the spread of F over the ~0.1 degree lobe and its
  // single-scattering loss).
  for (float strength : {1.0f, 0.5f})
    for (float theta : {0.0f, 30.0f, 60.0f, 80.0f}) {
      BsdfParams p{glm::vec3(0.0f), 0.0f, 0.5f};
      p.dielectricF0 = glm::vec3(0.0f);
      p.dielectricF90 = 0.0f;
      p.clearcoat = strength;
      p.clearcoatRoughness = 0.0f;
      const glm::vec3 wo = incident(theta);
      const double want = strength * test::refSchlick(glm::dvec3(0.04), wo.z).x;
      const Estimate e = albedo(p, wo, 20000, uint32_t(theta));
      EXPECT_NEAR(e.mean, want, 4 * e.sigma + 2e-3) << "coat " << strength << " theta " << theta;
    }
}

TEST(Layers, NoLayerIsTheBaseToTheBit) {
  // Sheen black and coat 0 leave the base exactly as before, whatever the layers'
  // roughnesses: no golden image moves for scenes without the extensions.
  Sampler s = testSampler(21);
  for (int i = 0; i < 2000; ++i) {
    BsdfParams a{glm::vec3(s.next(), s.next(), s.next()), s.next(), s.next()};
    a.transmission = s.next() < 0.5f ? 0.0f : s.next();
    BsdfParams b = a;
    b.sheenRoughness = s.next();
    b.clearcoatRoughness = s.next();
    const glm::vec3 wo = sampleCosineHemisphere(s.next2()), wi = sampleUniformSphere(s.next2());
    ASSERT_EQ(evalBsdf(a, wo, wi), evalBsdf(b, wo, wi));
    ASSERT_EQ(pdfBsdf(a, wo, wi), pdfBsdf(b, wo, wi));
    const glm::vec2 u = s.next2();
    ASSERT_EQ(sampleBsdf(a, wo, u).weight, sampleBsdf(b, wo, u).weight);
  }
}

TEST(Sheen, CharlieDistributionProjectsToUnitArea) {
  // Any microfacet distribution: the integral of D(h) cos theta_h over the hemisphere is 1
  // (Walter et al. 2007, eq. 4). Midpoint rule in theta (4096 steps; the peak at grazing h
  // of the sharpest alpha is ~4 degrees wide); 1e-3.
  for (float roughness : {0.045f, 0.2f, 0.5f, 1.0f}) {
    const float alpha = sheenRoughnessToAlpha(roughness);
    double sum = 0.0;
    const int n = 4096;
    for (int i = 0; i < n; ++i) {
      const double t = (i + 0.5) * (0.5 * M_PI / n);
      const glm::vec3 h(float(std::sin(t)), 0.0f, float(std::cos(t)));
      sum += charlieD(h, alpha) * std::cos(t) * std::sin(t) * 2.0 * M_PI * (0.5 * M_PI / n);
    }
    EXPECT_NEAR(sum, 1.0, 1e-3) << roughness;
    EXPECT_NEAR(charlieD(glm::vec3(0.6f, 0.0f, 0.8f), alpha), test::refCharlieD(0.8, alpha),
                1e-5 * test::refCharlieD(0.8, alpha) + 1e-30);  // float underflows below 1e-38
  }
}

TEST(Sheen, AlbedoTableMatchesAQuadratureOfTheReference) {
  // The table (integrated offline from the float lobe) against the double reference's
  // lobe, integrated here by the midpoint rule in (theta, phi), between the table's nodes.
  // Tolerance: the bilinear interpolation's error, 2 % relative + 3e-3 (E's curvature in
  // sqrt(cos) and roughness over one cell).
  for (double r : {0.12, 0.3, 0.5, 0.77, 1.0})
    for (double c : {0.03, 0.1, 0.3, 0.55, 0.9}) {
      const glm::dvec3 wo(std::sqrt(1.0 - c * c), 0.0, c);
      double sum = 0.0;
      const int nt = 256, np = 128;
      for (int i = 0; i < nt; ++i) {
        const double t = (i + 0.5) * (0.5 * M_PI / nt);
        for (int j = 0; j < np; ++j) {
          const double phi = (j + 0.5) * (M_PI / np);
          const glm::dvec3 wi = test::refDirection(t, phi);
          sum += test::refSheen(r, wo, wi) * wi.z * std::sin(t);
        }
      }
      const double want = 2.0 * sum * (0.5 * M_PI / nt) * (M_PI / np);
      EXPECT_NEAR(sheenAlbedo(float(c), float(r)), want, 0.02 * want + 3e-3)
          << "cos " << c << " roughness " << r;
    }
}

TEST(Layers, FiniteForEdgeInputs) {
  // NaN and out-of-range layer parameters clamp; grazing and normal wo stay finite.
  for (float bad : {std::nanf(""), -1.0f, 2.0f, 0.0f, 1.0f})
    for (float theta : {0.0f, 89.99f}) {
      BsdfParams p{glm::vec3(0.5f), 0.0f, 0.5f};
      p.clearcoat = bad;
      p.clearcoatRoughness = bad;
      p.sheenColor = glm::vec3(bad);
      p.sheenRoughness = bad;
      const glm::vec3 wo = incident(theta);
      Sampler s = testSampler(8);
      for (int i = 0; i < 200; ++i) {
        const BsdfSample b = sampleBsdf(p, wo, s.next2());
        ASSERT_TRUE(isFinite(b.weight) && std::isfinite(b.pdf)) << bad << " " << theta;
        ASSERT_TRUE(isFinite(evalBsdf(p, wo, sampleUniformSphere(s.next2()))));
      }
    }
}

}  // namespace
}  // namespace photovr
