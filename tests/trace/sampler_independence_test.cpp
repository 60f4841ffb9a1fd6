// The draws of one path are independent of each other under the Sobol sampler: each draw's
// index is shuffled by a seed of its own (core/sobol.h), so two draws are two differently
// ordered copies of the sequence. Without the shuffle two draws would be the same sequence
// under two nested scrambles, and each 2^-k interval of one would pair with a single 2^-k
// interval of the other: a light sample and a BSDF sample of the same vertex would move in
// lockstep over the samples of a pixel.
#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include "trace/rng.h"

namespace photovr {
namespace {

constexpr uint32_t kN = 256;  // samples of one pixel: the sample index 0..255

Sampler samplerOf(uint32_t pixel, uint32_t index, uint32_t bounce) {
  return Sampler::make({.pixel = pixel,
                        .sample = index,
                        .bounce = bounce,
                        .samplesPerFrame = kN,
                        .kind = SamplerKind::Sobol});
}

// The fraction of a pixel's kN pairs with both coordinates below 1/2.
using Pair = std::function<glm::vec2(uint32_t pixel, uint32_t index)>;
double lowerLeftShare(const Pair& pair, uint32_t pixel) {
  uint32_t n = 0;
  for (uint32_t i = 0; i < kN; ++i) {
    const glm::vec2 p = pair(pixel, i);
    n += p.x < 0.5f && p.y < 0.5f;
  }
  return double(n) / kN;
}

// Independent, each coordinate stratified: the count in the quadrant has the variance of a
// Latin hypercube's, N ab (1 - a)(1 - b) = 16 at a = b = 1/2, so its share is 1/4 with a
// standard deviation of 4 / 256 = 0.016 (random points: 0.027). Draws in lockstep put 0 or
// 1/2 there. 0.1 is 6 standard deviations of the independent case and far from lockstep.
void expectIndependent(const Pair& pair, const char* what) {
  for (uint32_t pixel = 0; pixel < 16; ++pixel)
    EXPECT_NEAR(lowerLeftShare(pair, pixel), 0.25, 0.1) << what << ", pixel " << pixel;
}

// The first two 2D draws of one vertex: x of each, or y of each.
glm::vec2 twoDraws(uint32_t pixel, uint32_t index, bool y) {
  Sampler s = samplerOf(pixel, index, 0);
  const glm::vec2 a = s.next2(), b = s.next2();
  return y ? glm::vec2(a.y, b.y) : glm::vec2(a.x, b.x);
}

TEST(SamplerIndependence, TwoDimensionalDrawsOfOneVertex) {
  expectIndependent([](uint32_t px, uint32_t i) { return twoDraws(px, i, false); },
                    "x of draws 0 and 1");
  expectIndependent([](uint32_t px, uint32_t i) { return twoDraws(px, i, true); },
                    "y of draws 0 and 1");
}

TEST(SamplerIndependence, OneAndTwoDimensionalDrawsAndBounces) {
  expectIndependent(
      [](uint32_t px, uint32_t i) {
        Sampler s = samplerOf(px, i, 0);
        const float a = s.next();
        return glm::vec2(a, s.next2().x);
      },
      "a 1D draw and the next 2D draw");
  expectIndependent(
      [](uint32_t px, uint32_t i) {
        return glm::vec2(samplerOf(px, i, 0).next2().x, samplerOf(px, i, 1).next2().x);
      },
      "the first 2D draws of bounces 0 and 1");
}

TEST(SamplerIndependence, TheTestSeesLockstep) {
  // The same draw twice: the diagonal, all pairs in the lower-left or upper-right quadrant,
  // so the share is exactly that of the points below 1/2 on one axis, 1/2.
  EXPECT_EQ(
      lowerLeftShare(
          [](uint32_t px, uint32_t i) { return glm::vec2(samplerOf(px, i, 0).next2().x); }, 3),
      0.5);
}

}  // namespace
}  // namespace photovr
