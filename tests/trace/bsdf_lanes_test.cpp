// The BSDF stage (trace/bsdf_lanes.h): a vertex sampled in SIMD lanes gets the bits it gets
// alone, and the lanes' sine and cosine are those of the angle to float precision.
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

TEST(BsdfLanes, AnEmptyBatchIsNothing) {
  sampleBrdfs({}, {}, {});
}

}  // namespace
}  // namespace photovr
