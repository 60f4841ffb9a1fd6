// SSIM (core/perceptual_metrics.h) against properties that follow from its definition
// (Wang et al. 2004, eq. 13): exactness on identical images, the closed forms for constant
// images and for a constant offset, symmetry, and monotone decrease with added noise.
#include "core/perceptual_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace photovr {
namespace {

constexpr int kW = 32, kH = 32;  // 22 x 22 valid windows: an even count of each row parity
constexpr double kC1 = kSsimK1 * kSsimK1;

// SSIM's luminance term for two window means (eq. 6 with C1 = (K1 L)^2, L = 1).
double luminanceTerm(double a, double b) {
  return (2.0 * a * b + kC1) / (a * a + b * b + kC1);
}

std::vector<float> constant(float v) {
  return std::vector<float>(size_t(kW) * kH, v);
}

// Horizontal stripes a + s (-1)^row: every window has the same variance and one of two means.
std::vector<float> stripes(float a, float s) {
  std::vector<float> img(size_t(kW) * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) img[size_t(y) * kW + x] = a + ((y & 1) ? -s : s);
  return img;
}

std::vector<float> texture() {
  std::vector<float> img(size_t(kW) * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      img[size_t(y) * kW + x] = 0.5f + 0.3f * std::sin(0.4f * x) * std::cos(0.3f * y);
  return img;
}

std::vector<float> withNoise(std::vector<float> img, float sigma, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> n(0.0f, sigma);
  for (float& v : img) v += n(rng);
  return img;
}

TEST(Ssim, IdenticalImagesGiveExactlyOne) {
  // The implementation evaluates numerator and denominator with the same operations when
  // x == y, so the quotient is 1 without rounding error: no tolerance.
  const auto img = withNoise(texture(), 0.1f, 1);
  EXPECT_EQ(ssim(img, img, kW, kH), 1.0);
  EXPECT_EQ(ssim(constant(0.0f), constant(0.0f), kW, kH), 1.0);
}

TEST(Ssim, TwoConstantImagesMatchTheClosedForm) {
  // Zero variance: the contrast-structure term is C2 / C2 = 1, SSIM is the luminance term.
  // 1e-12: float inputs are exact in double, so only a few roundings of the sums remain.
  for (auto [a, b] : {std::pair{0.3f, 0.7f}, {0.0f, 1.0f}, {0.5f, 0.52f}})
    EXPECT_NEAR(ssim(constant(a), constant(b), kW, kH), luminanceTerm(a, b), 1e-12) << a << b;
}

TEST(Ssim, ConstantOffsetOfStripesMatchesTheClosedForm) {
  // y = x + c keeps every window's variance and covariance equal, so the contrast-structure
  // term is 1 and SSIM averages the luminance term over the two window means
  // a +- s D, D = sum_k g_k (-1)^k (the 1-D Gaussian's alternating sum).
  double g[kSsimWindow], sum = 0.0, d = 0.0;
  for (int k = 0; k < kSsimWindow; ++k) {
    const double t = k - kSsimWindow / 2;
    sum += g[k] = std::exp(-t * t / (2.0 * kSsimSigma * kSsimSigma));
  }
  for (int k = 0; k < kSsimWindow; ++k) d += (k & 1 ? -1.0 : 1.0) * g[k] / sum;
  // Binary fractions: every pixel value and sum is exact in float.
  const float a = 0.375f, s = 0.25f, c = 0.125f;
  const double expected =
      0.5 * (luminanceTerm(a + s * d, a + s * d + c) + luminanceTerm(a - s * d, a - s * d + c));
  // 1e-12: the variances are differences of window sums (~0.2) that cancel to s^2 (1 - D^2),
  // ~0.06; double rounding of the 242-term sums leaves ~1e-14, far inside this bound.
  EXPECT_NEAR(ssim(stripes(a, s), stripes(a + c, s), kW, kH), expected, 1e-12);
  EXPECT_LT(expected, 1.0);
}

TEST(Ssim, IsSymmetric) {
  // Swapping the images only reorders commutative operations: equal to the last bit.
  const auto x = texture(), y = withNoise(texture(), 0.05f, 2);
  EXPECT_EQ(ssim(x, y, kW, kH), ssim(y, x, kW, kH));
}

TEST(Ssim, DecreasesAsNoiseGrows) {
  // Each noise level about triples the standard deviation. Over seeds 1..7 the SSIM ranges
  // of adjacent levels do not overlap (closest: 0.958 at sigma 0.03 against 0.994 at 0.01),
  // so the order does not hang on the seed.
  const auto clean = texture();
  double previous = 1.0;
  for (float sigma : {0.01f, 0.03f, 0.1f, 0.3f}) {
    const double v = ssim(clean, withNoise(clean, sigma, 3), kW, kH);
    EXPECT_LT(v, previous) << "sigma " << sigma;
    EXPECT_GT(v, -1.0);
    previous = v;
  }
}

TEST(Ssim, RejectsImagesSmallerThanTheWindowOrOfUnequalSize) {
  const std::vector<float> small(10 * 10, 0.5f);
  EXPECT_THROW(ssim(small, small, 10, 10), std::invalid_argument);
  EXPECT_THROW(ssim(constant(0.5f), small, kW, kH), std::invalid_argument);
}

TEST(SsimDisplay, ComparesTheToneMappedLuminance) {
  // Linear HDR values go through the display transform first: identical images give 1, and
  // two constant images give the closed form on their display luminance.
  const std::vector<glm::vec3> a(size_t(kW) * kH, glm::vec3(0.2f, 0.3f, 0.1f));
  const std::vector<glm::vec3> b(size_t(kW) * kH, glm::vec3(5.0f, 4.0f, 3.0f));
  EXPECT_EQ(ssimDisplay(a, a, kW, kH), 1.0);
  const double la = displayLuminance(a)[0], lb = displayLuminance(b)[0];
  EXPECT_GT(lb, 0.9);  // tone-mapped, not clipped at the linear value
  EXPECT_LE(lb, 1.0);
  EXPECT_NEAR(ssimDisplay(a, b, kW, kH), luminanceTerm(la, lb), 1e-9);
}

}  // namespace
}  // namespace photovr
