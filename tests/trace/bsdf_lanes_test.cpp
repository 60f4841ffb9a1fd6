// The BSDF stage (trace/bsdf_stage.h, trace/bsdf_lanes.h): a vertex prepared, evaluated
// and sampled in SIMD lanes gets the bits it gets alone, and the lanes' sine and cosine
// are those of the angle to float precision.
#include "trace/bsdf_lanes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace photovr {
namespace {

TEST(BsdfLanes, SineAndCosineOfATurnAreWithinFourUlpOfOne) {
  // 2^20 points of [0, 1) against double precision. The quadrant comes off exactly; the
  // quarter angle's rounding (half an ulp of <= pi/4), the Taylor tail (< 1.8e-9) and
  // Horner's roundings (about an ulp of a result <= 1, 6e-8 each) stay within 4 ulp of 1.
  constexpr double kTolerance = 4.0 * 0x1p-24;
  double worst = 0.0;
  for (uint32_t k = 0; k < (1u << 20); ++k) {
    const float u = float(k) * 0x1p-20f;
    float s, c;
    lanes::sinCos2Pi(u, s, c);
    const double phi = 2.0 * M_PI * double(u);
    worst = std::max({worst, std::abs(s - std::sin(phi)), std::abs(c - std::cos(phi))});
  }
  EXPECT_LT(worst, kTolerance);
  // The float just below 1 is a turn less 2 pi 2^-24: sine negative, cosine 1.
  float s, c;
  lanes::sinCos2Pi(0x1.fffffep-1f, s, c);
  EXPECT_LT(s, 0.0f);
  EXPECT_NEAR(s, -2.0 * M_PI * 0x1p-24, 1e-12);
  EXPECT_EQ(c, 1.0f);
}

// Vertices over the whole range: roughness 0 and 1, metals, black and white bases, views
// from normal incidence to grazing and below the surface.
std::vector<BsdfVertex> randomVertices(size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const auto pick = [&](float a, float b) {
    return u(rng) < 0.2f ? (u(rng) < 0.5f ? a : b) : u(rng);
  };
  std::vector<BsdfVertex> vertices;
  for (size_t i = 0; i < count; ++i) {
    BsdfParams p;
    p.baseColor = glm::vec3(pick(0, 1), pick(0, 1), pick(0, 1));
    p.metallic = pick(0, 1);
    p.roughness = pick(0, 1);
    const float cosTheta = i % 50 == 0 ? -0.3f : i % 50 == 1 ? 0.0f : pick(1e-4f, 1.0f);
    const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    const float phi = 6.2831853f * u(rng);
    vertices.push_back(
        prepareBsdf(p, {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta}));
  }
  return vertices;
}

TEST(BsdfLanes, SamplesInLanesEqualOneByOneBitForBit) {
  // 1003: no multiple of 8, so a partly filled group runs too.
  const std::vector<BsdfVertex> vertices = randomVertices(1003, 11);
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<const BsdfVertex*> pointers;
  std::vector<glm::vec2> numbers;
  for (const BsdfVertex& v : vertices) {
    pointers.push_back(&v);
    numbers.push_back({u(rng), u(rng)});
  }
  numbers[3] = {0.0f, 0.0f};  // the concentric map's centre
  numbers[4] = {0x1.fffffep-1f, 0x1.fffffep-1f};
  std::vector<BsdfSample> batch(vertices.size());
  sampleBrdfs(pointers, numbers, batch);
  size_t valid = 0;
  for (size_t i = 0; i < vertices.size(); ++i) {
    const BsdfSample one = sampleBrdf(vertices[i], numbers[i]);
    const BsdfSample viaBsdf = sampleBsdf(vertices[i], numbers[i]);
    for (const BsdfSample* other : {static_cast<const BsdfSample*>(&batch[i]), &viaBsdf}) {
      EXPECT_EQ(other->wi, one.wi) << i;
      EXPECT_EQ(other->f, one.f) << i;
      EXPECT_EQ(other->fDiffuse, one.fDiffuse) << i;
      EXPECT_EQ(other->pdf, one.pdf) << i;
      EXPECT_EQ(other->weight, one.weight) << i;
      EXPECT_EQ(other->specularLobe, one.specularLobe) << i;
    }
    valid += one.valid();
  }
  EXPECT_GT(valid, vertices.size() / 2);  // most vertices face the viewer and sample
}

// Every field a vertex has, compared (== on floats: bit for bit but for the sign of 0).
void expectSameVertex(const BsdfVertex& a, const BsdfVertex& b, size_t i) {
  EXPECT_EQ(a.wo, b.wo) << i;
  EXPECT_EQ(a.alpha, b.alpha) << i;
  EXPECT_EQ(a.f0, b.f0) << i;
  EXPECT_EQ(a.diffuse, b.diffuse) << i;
  EXPECT_EQ(a.f90, b.f90) << i;
  EXPECT_EQ(a.fresnelWo, b.fresnelWo) << i;
  EXPECT_EQ(a.g1OverCosWo, b.g1OverCosWo) << i;
  EXPECT_EQ(a.specularProbability, b.specularProbability) << i;
  EXPECT_EQ(a.glass, b.glass) << i;
  EXPECT_EQ(a.brdfWeight, b.brdfWeight) << i;
  EXPECT_EQ(a.glassProbability, b.glassProbability) << i;
  EXPECT_EQ(a.reflectProbability, b.reflectProbability) << i;
  EXPECT_EQ(a.eta, b.eta) << i;
  EXPECT_EQ(a.tint, b.tint) << i;
  EXPECT_EQ(a.thinWalled, b.thinWalled) << i;
  EXPECT_EQ(a.layered, b.layered) << i;
  EXPECT_EQ(a.coat, b.coat) << i;
  EXPECT_EQ(a.coatAlpha, b.coatAlpha) << i;
  EXPECT_EQ(a.coatG1OverCosWo, b.coatG1OverCosWo) << i;
  EXPECT_EQ(a.coatFresnelWo, b.coatFresnelWo) << i;
  EXPECT_EQ(a.coatTilted, b.coatTilted) << i;
  EXPECT_EQ(a.coatNormal, b.coatNormal) << i;
  EXPECT_EQ(a.coatWo, b.coatWo) << i;
  EXPECT_EQ(a.sheenColor, b.sheenColor) << i;
  EXPECT_EQ(a.sheenRoughness, b.sheenRoughness) << i;
  EXPECT_EQ(a.sheenAlpha, b.sheenAlpha) << i;
  EXPECT_EQ(a.sheenMax, b.sheenMax) << i;
  EXPECT_EQ(a.sheenLambdaWo, b.sheenLambdaWo) << i;
  EXPECT_EQ(a.sheenAlbedoWo, b.sheenAlbedoWo) << i;
  EXPECT_EQ(a.coatProbability, b.coatProbability) << i;
  EXPECT_EQ(a.sheenProbability, b.sheenProbability) << i;
}

TEST(BsdfLanes, VerticesPreparedAndEvaluatedInLanesEqualOneByOneBitForBit) {
  // Parameters in and out of range, NaN and infinite ones (prepareBsdf's clamps), glTF's
  // specular extension's f0 and f90, with views and light directions over the sphere.
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float odd[] = {-0.5f, 1.5f, NAN, INFINITY, 0.0f, 1.0f};
  const auto value = [&] { return u(rng) < 0.15f ? odd[rng() % 6] : u(rng); };
  const auto direction = [&] {
    const float z = 2.0f * u(rng) - 1.0f, r = std::sqrt(1.0f - z * z), phi = 6.2831853f * u(rng);
    return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
  };
  constexpr size_t kCount = 1003;  // no multiple of 8
  std::vector<BsdfParams> params(kCount);
  std::vector<BsdfVertex> vertices(kCount);
  std::vector<BsdfEval> evals(kCount), seconds(kCount);
  std::vector<BrdfPrepareJob> jobs;
  for (size_t i = 0; i < kCount; ++i) {
    BsdfParams& p = params[i];
    p.baseColor = {value(), value(), value()};
    p.metallic = value();
    p.roughness = value();
    if (i % 3 == 0) p.dielectricF0 = {value(), value(), value()};
    if (i % 5 == 0) p.dielectricF90 = value();
    ASSERT_TRUE(plainBsdf(p));
    // Every other vertex also at a second direction (a reused sample's bounce).
    jobs.push_back({&p, direction(), direction(), &vertices[i], &evals[i], direction(),
                    i % 2 ? &seconds[i] : nullptr});
  }
  prepareBrdfs(jobs);
  size_t nonZero = 0;
  for (size_t i = 0; i < kCount; ++i) {
    const BsdfVertex one = prepareBsdf(params[i], jobs[i].wo);
    expectSameVertex(vertices[i], one, i);
    const BsdfEval e = evalBsdfAndPdf(one, jobs[i].wi);
    EXPECT_EQ(evals[i].f.diffuse, e.f.diffuse) << i;
    EXPECT_EQ(evals[i].f.specular, e.f.specular) << i;
    EXPECT_EQ(evals[i].pdf, e.pdf) << i;
    const BsdfEval second = i % 2 ? evalBsdfAndPdf(one, jobs[i].wi2) : BsdfEval{};
    EXPECT_EQ(seconds[i].f.diffuse, second.f.diffuse) << i;
    EXPECT_EQ(seconds[i].f.specular, second.f.specular) << i;
    EXPECT_EQ(seconds[i].pdf, second.pdf) << i;
    nonZero += e.pdf > 0.0f;
  }
  EXPECT_GT(nonZero, kCount / 8);  // a quarter of the pairs are both above the surface
}

TEST(BsdfLanes, AnEmptyBatchIsNothing) {
  sampleBrdfs({}, {}, {});
  prepareBrdfs({});
}

}  // namespace
}  // namespace photovr
