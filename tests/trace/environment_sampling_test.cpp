#include "trace/environment_sampling.h"

#include <cmath>

#include <gtest/gtest.h>

#include "tests/trace/chi_square.h"
#include "trace/rng.h"

namespace photovr {
namespace {

using test::chiSquareTest;
using test::Histogram;

Sampler testSampler(uint32_t seed) {
  return Sampler::make({.pixel = seed, .seed = 4242u});
}

// Round trips through asin lose ~ulp(1) / cos(elevation) rad near the poles; for
// |v - 0.5| <= 0.49 that is < 2e-6 in v. 1e-5 leaves room for atan2 and cos/sin.
constexpr float kUvTol = 1e-5f;

TEST(Equirect, AxesMapWhereBlenderAndThreeJsPutThem) {
  EXPECT_NEAR(directionToEquirect({0, 1, 0}).y, 1.0f, kUvTol);  // up = top row
  EXPECT_NEAR(directionToEquirect({0, -1, 0}).y, 0.0f, kUvTol);
  EXPECT_NEAR(directionToEquirect({1, 0, 0}).x, 0.5f, kUvTol);
  EXPECT_NEAR(directionToEquirect({1, 0, 0}).y, 0.5f, kUvTol);
  EXPECT_NEAR(directionToEquirect({0, 0, 1}).x, 0.75f, kUvTol);
  EXPECT_NEAR(directionToEquirect({0, 0, -1}).x, 0.25f, kUvTol);
  const float uMinusX = directionToEquirect({-1, 0, 0}).x;
  EXPECT_TRUE(std::abs(uMinusX) < kUvTol || std::abs(uMinusX - 1.0f) < kUvTol) << uMinusX;
  // Latitude-linear: 45 degrees elevation is v = 0.75 (equal-area would give 0.854).
  EXPECT_NEAR(directionToEquirect(glm::vec3(1, 1, 0)).y, 0.75f, kUvTol);
  EXPECT_NEAR(equirectToDirection({0.75f, 0.5f}).z, 1.0f, kUvTol);
  EXPECT_NEAR(equirectToDirection({0.3f, 1.0f}).y, 1.0f, kUvTol);
}

TEST(Equirect, RoundTripsBothWays) {
  for (float u = 0.005f; u < 1.0f; u += 0.01f)
    for (float v = 0.01f; v < 1.0f; v += 0.01f) {
      const glm::vec3 d = equirectToDirection({u, v});
      EXPECT_NEAR(glm::length(d), 1.0f, 1e-6f);
      const glm::vec2 uv = directionToEquirect(d);
      EXPECT_NEAR(uv.x, u, kUvTol);
      EXPECT_NEAR(uv.y, v, kUvTol);
    }
  Sampler s = testSampler(1);
  for (int i = 0; i < 1000; ++i) {
    const glm::vec3 d = sampleUniformSphere(s.next2());
    if (std::abs(d.y) > 0.999f) continue;  // azimuth is ill-conditioned at the poles
    // 2e-5: the direction's own rounding is amplified by 1/cos(elevation) <= 22 in x, z.
    EXPECT_NEAR(glm::length(equirectToDirection(directionToEquirect(d)) - d), 0.0f, 2e-5f);
  }
}

// A panorama whose pixels hold their own centre (u, v).
Environment selfEncodingPanorama(int w, int h) {
  Environment env;
  env.type = Environment::Type::Map;
  env.width = w;
  env.height = h;
  env.intensity = 1.0f;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) env.pixels.push_back({(i + 0.5f) / w, 1.0f - (j + 0.5f) / h, 0.0f});
  return env;
}

TEST(Equirect, LookupReadsThePixelUnderTheDirection) {
  // Nearest lookup returns the centre of the pixel containing d: within half a pixel of
  // d's own (u, v), u measured around the seam. 1e-5 for the float mapping, as above.
  const int w = 64, h = 32;
  const Environment env = selfEncodingPanorama(w, h);
  Sampler s = testSampler(2);
  for (int i = 0; i < 20000; ++i) {
    const glm::vec3 d = sampleUniformSphere(s.next2());
    const glm::vec2 uv = directionToEquirect(d);
    const glm::vec3 got = lookupEnvironment(env, d);
    const float du = std::abs(got.x - uv.x);
    ASSERT_LE(std::min(du, 1.0f - du), 0.5f / w + kUvTol) << d.x << " " << d.y << " " << d.z;
    ASSERT_LE(std::abs(got.y - uv.y), 0.5f / h + kUvTol);
  }
  // The top row is up, the first column is -X turning towards -Z.
  EXPECT_NEAR(lookupEnvironment(env, {0, 1, 0}).y, 1.0f - 0.5f / h, 1e-6f);
  EXPECT_NEAR(lookupEnvironment(env, glm::normalize(glm::vec3(-1, 0, -0.01f))).x, 0.5f / w, 1e-6f);
}

TEST(Environment, ConstantAndSkyAndNone) {
  Environment env;
  EXPECT_EQ(lookupEnvironment(env, {0, 1, 0}), glm::vec3(0.0f));
  env.type = Environment::Type::Constant;
  env.constant = glm::vec3(0.5f, 1.0f, 2.0f);
  env.intensity = 2.0f;
  EXPECT_EQ(lookupEnvironment(env, {1, 0, 0}), glm::vec3(1.0f, 2.0f, 4.0f));
  env.type = Environment::Type::Sky;
  env.zenithColor = glm::vec3(0, 0, 1);
  env.horizonColor = glm::vec3(1, 1, 1);
  env.groundColor = glm::vec3(0.1f);
  EXPECT_EQ(lookupEnvironment(env, {0, 1, 0}), glm::vec3(0, 0, 2));
  EXPECT_EQ(lookupEnvironment(env, {1, 0, 0}), glm::vec3(2.0f));
  EXPECT_EQ(lookupEnvironment(env, {0, -1, 0}), glm::vec3(0.2f));
  EXPECT_TRUE(isFinite(lookupEnvironment(env, glm::vec3(std::nanf("")))));
  EXPECT_TRUE(isFinite(lookupEnvironment(selfEncodingPanorama(4, 2), glm::vec3(std::nanf("")))));
}

// A 32 x 16 map: a dim gradient, a bright 2 x 1 spot above the horizon and a black patch,
// the features an HDR sky has (sun, zero-radiance regions, smooth variation).
Environment spotMap() {
  Environment env;
  env.type = Environment::Type::Map;
  env.width = 32;
  env.height = 16;
  env.intensity = 1.5f;
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 32; ++i) env.pixels.push_back(glm::vec3(0.1f + 0.02f * i, 0.2f, 0.05f * j));
  env.pixels[5 * 32 + 20] = env.pixels[5 * 32 + 21] = glm::vec3(200.0f, 180.0f, 150.0f);
  for (int i = 0; i < 6; ++i) env.pixels[12 * 32 + i] = glm::vec3(0.0f);
  return env;
}

Environment clearSky() {
  Environment env;
  env.type = Environment::Type::Sky;
  env.zenithColor = glm::vec3(0.12f, 0.22f, 0.45f);
  env.horizonColor = glm::vec3(0.4f, 0.45f, 0.5f);
  env.groundColor = glm::vec3(0.12f, 0.11f, 0.1f);
  return env;
}

Environment constantEnv() {
  Environment env;
  env.type = Environment::Type::Constant;
  env.constant = glm::vec3(0.7f);
  return env;
}

// Directions on the (theta / pi, phi) square, theta from +Y and phi the equirect u: the
// solid angle is dw = 2 pi^2 sin(theta) dx dy.
glm::vec3 gridDirection(double x, double y) {
  return equirectToDirection({float(y), float(1.0 - x)});
}
glm::vec2 gridCoords(const glm::vec3& d) {
  const glm::vec2 uv = directionToEquirect(d);
  return {1.0f - uv.y, uv.x - std::floor(uv.x)};
}
double gridJacobian(double x) {
  return 2.0 * M_PI * M_PI * std::sin(M_PI * x);
}
// Directions on the ((1 + d.y) / 2, phi / 2 pi) square, of constant Jacobian 4 pi.
glm::vec3 zonalDirection(double x, double y) {
  const double dy = 2.0 * x - 1.0, r = std::sqrt(1.0 - dy * dy), phi = 2.0 * M_PI * y;
  return glm::vec3(float(r * std::cos(phi)), float(dy), float(r * std::sin(phi)));
}

class EnvironmentSamplerTest : public testing::TestWithParam<int> {
 protected:
  void SetUp() override {
    const int which = GetParam();
    env_ = which == 0 ? spotMap() : which == 1 ? clearSky() : constantEnv();
    sampler_ = EnvironmentSampler(env_);
  }
  Environment env_;
  EnvironmentSampler sampler_;
};

TEST_P(EnvironmentSamplerTest, PdfIntegratesToOne) {
  // Midpoint rule on 128 x 256 cells that refine the sampler's own: the map's 32 x 16 pixels
  // on the (theta, phi) square, dw = 2 pi^2 sin(theta) dx dy; the sky's and the constant's
  // 64 bands of y = d.y, on the (y, phi) square, dw = dy dphi (4 pi over the square). Each
  // cell lies inside one of the sampler's, where pdf * Jacobian is constant, so the rule is
  // exact but for float rounding of the direction, worst at the poles (sin theta from a
  // float cos ~ 1 - theta^2/2): measured < 1e-6, bound 1e-4.
  const int nx = 128, ny = 256;
  const bool zonal = env_.type != Environment::Type::Map;
  double sum = 0.0;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      const double x = (i + 0.5) / nx, y = (j + 0.5) / ny;
      sum += zonal ? sampler_.pdf(zonalDirection(x, y)) * 4.0 * M_PI
                   : sampler_.pdf(gridDirection(x, y)) * gridJacobian(x);
    }
  EXPECT_NEAR(sum / (double(nx) * ny), 1.0, 1e-4);
}

TEST_P(EnvironmentSamplerTest, SamplesAgreeWithPdfAndLookup) {
  Sampler s = testSampler(3);
  for (int i = 0; i < 20000; ++i) {
    const EnvironmentSample e = sampler_.sample(s.next2());
    ASSERT_TRUE(e.valid());
    ASSERT_NEAR(glm::length(e.direction), 1.0f, 1e-5f);
    ASSERT_EQ(e.pdf, sampler_.pdf(e.direction));  // computed by pdf() itself
    ASSERT_EQ(e.radiance, lookupEnvironment(env_, e.direction));
  }
}

TEST_P(EnvironmentSamplerTest, ChiSquare) {
  Histogram h(20, 40);  // 9 x 9 degree cells, not aligned with the map's pixels
  Sampler s = testSampler(4 + GetParam());
  for (int i = 0; i < 200000; ++i) {
    const EnvironmentSample e = sampler_.sample(s.next2());
    if (e.valid())
      h.add(gridCoords(e.direction));
    else
      h.addFailure();
  }
  const auto r = chiSquareTest(
      h, [&](double x, double y) { return sampler_.pdf(gridDirection(x, y)) * gridJacobian(x); });
  EXPECT_TRUE(r.passed()) << r.describe();
}

INSTANTIATE_TEST_SUITE_P(MapSkyConstant, EnvironmentSamplerTest, testing::Values(0, 1, 2));

TEST(EnvironmentSampler, PdfIsLuminanceTimesSinThetaOverTheJacobian) {
  // Independent of Distribution2D: the density of pixel (i, j) is its weight
  // lum * sin(theta_j) over the mean weight, divided by 2 pi^2 sin(theta) (pbrt eq. 12.12).
  // Float sums of 512 weights vs double: 1e-4 relative.
  const Environment env = spotMap();
  const EnvironmentSampler sampler(env);
  double sum = 0.0;
  for (int j = 0; j < env.height; ++j)
    for (int i = 0; i < env.width; ++i)
      sum += luminance(env.pixels[j * env.width + i]) * std::sin(M_PI * (j + 0.5) / env.height);
  const double mean = sum / (env.width * env.height);
  for (glm::ivec2 p :
       {glm::ivec2(20, 5), glm::ivec2(3, 12), glm::ivec2(0, 0), glm::ivec2(31, 15)}) {
    const glm::vec2 uv((p.x + 0.3f) / env.width, 1.0f - (p.y + 0.6f) / env.height);
    const glm::vec3 d = equirectToDirection(uv);
    const double theta = M_PI * (1.0 - uv.y);
    const double weight =
        luminance(env.pixels[p.y * env.width + p.x]) * std::sin(M_PI * (p.y + 0.5) / env.height);
    const double expected = weight / mean / (2.0 * M_PI * M_PI * std::sin(theta));
    EXPECT_NEAR(sampler.pdf(d), expected, 1e-4 * expected + 1e-12) << p.x << " " << p.y;
  }
  // The bright spot takes most samples: 2 of 512 pixels, ~80 % of the weight (2 x 182 x
  // sin 62 deg against ~510 x 0.25 x 0.64 for the rest).
  int inSpot = 0;
  Sampler s = testSampler(5);
  for (int i = 0; i < 1000; ++i)
    if (luminance(sampler.sample(s.next2()).radiance) > 100.0f) ++inSpot;
  EXPECT_GT(inSpot, 700);
}

TEST(EnvironmentSampler, SkyPdfIsItsBandsLuminanceOverTheMeanAtAnyAzimuth) {
  // Independent of Distribution1D: band k of y = d.y in [-1 + 2k/64, -1 + 2(k+1)/64) has
  // density lum(sky at its centre) / mean over the bands / (4 pi), whatever the azimuth
  // (dw = dy dphi). Float sums of 64 weights vs double: 1e-5 relative.
  const Environment env = clearSky();
  const EnvironmentSampler sampler(env);
  const int n = EnvironmentSampler::kZones;
  auto bandLuminance = [&](int k) {
    const double y = -1.0 + 2.0 * (k + 0.5) / n;
    return double(luminance(skyRadiance(env, glm::vec3(float(std::sqrt(1.0 - y * y)), y, 0))));
  };
  double mean = 0.0;
  for (int k = 0; k < n; ++k) mean += bandLuminance(k) / n;
  for (int k : {0, 20, n / 2 - 1, n / 2, 50, n - 1})
    for (double phi : {0.1, 2.0, 4.5}) {
      const double y = -1.0 + 2.0 * (k + 0.3) / n, r = std::sqrt(1.0 - y * y);
      const glm::vec3 d(float(r * std::cos(phi)), float(y), float(r * std::sin(phi)));
      const double expected = bandLuminance(k) / mean / (4.0 * M_PI);
      EXPECT_NEAR(sampler.pdf(d), expected, 1e-5 * expected) << k << " " << phi;
    }
  // The horizon is a band edge: just below it the ground's density, just above the sky's.
  const float below = sampler.pdf({1.0f, -1e-6f, 0.0f}), above = sampler.pdf({1.0f, 1e-6f, 0.0f});
  EXPECT_NEAR(below, bandLuminance(n / 2 - 1) / mean / (4.0 * M_PI), 1e-5 * below);
  EXPECT_NEAR(above, bandLuminance(n / 2) / mean / (4.0 * M_PI), 1e-5 * above);
  EXPECT_GT(above, 2.0f * below);  // the built-in test sky's horizon outshines its ground
}

TEST(EnvironmentSampler, NoneAndBadMapsGiveNoSamples) {
  const Environment none;
  const EnvironmentSampler a(none);
  EXPECT_TRUE(a.empty());
  EXPECT_FALSE(a.sample({0.5f, 0.5f}).valid());
  EXPECT_EQ(a.pdf({0, 1, 0}), 0.0f);
  Environment bad;
  bad.type = Environment::Type::Map;
  bad.width = 4;
  bad.height = 2;  // no pixels
  EXPECT_TRUE(EnvironmentSampler(bad).empty());
  const EnvironmentSampler def;
  EXPECT_FALSE(def.sample({0.1f, 0.1f}).valid());
}

}  // namespace
}  // namespace photovr
