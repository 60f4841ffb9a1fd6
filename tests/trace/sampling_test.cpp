#include "trace/sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "tests/trace/chi_square.h"
#include "trace/rng.h"

namespace photovr {
namespace {

using test::chiSquareTest;
using test::Histogram;

// 2e5 samples put ~250 in each of 800 cells: enough to see a 10 % error in any cell (a
// 1.6 sigma shift per cell, ~1000 in the statistic summed over a lobe), fast under ASan.
constexpr int kSamples = 200000;

Sampler testSampler(uint32_t seed) {
  return Sampler::make({.pixel = seed, .seed = 12345u});
}

// --- The chi-square machinery itself. -------------------------------------------------

TEST(ChiSquare, PValuesMatchTables) {
  // Critical values at p = 0.05 and 0.01 from NIST/SEMATECH e-Handbook, table 1.3.6.7.4;
  // printed to 3 decimals, hence 1e-4 on p.
  EXPECT_NEAR(test::chiSquarePValue(3.841, 1), 0.05, 1e-4);
  EXPECT_NEAR(test::chiSquarePValue(18.307, 10), 0.05, 1e-4);
  EXPECT_NEAR(test::chiSquarePValue(63.691, 40), 0.01, 1e-4);
  EXPECT_NEAR(test::chiSquarePValue(135.807, 100), 0.01, 1e-4);
  // dof 2: p = exp(-x/2) exactly; the continued fraction converges to ~1e-15.
  EXPECT_NEAR(test::chiSquarePValue(7.0, 2), std::exp(-3.5), 1e-12);
}

TEST(ChiSquare, AdaptiveSimpsonIntegratesAPeak) {
  // A Gaussian of width 1e-3 in [0, 1]: sqrt(pi) * 1e-3 (erf(..) = 1 to double precision).
  const double v = test::integrate1D(
      [](double x) { return std::exp(-(x - 0.3) * (x - 0.3) * 1e6); }, 0.0, 1.0, 1e-12, 4, 30);
  EXPECT_NEAR(v, std::sqrt(M_PI) * 1e-3, 1e-9);
}

TEST(ChiSquare, RejectsAWrongDensity) {
  // Uniform samples against density 2x on [0,1]^2: a gross error must be detected.
  Sampler s = testSampler(1);
  Histogram h(10, 10);
  for (int i = 0; i < 20000; ++i) h.add(s.next2());
  EXPECT_TRUE(chiSquareTest(h, [](double, double) { return 1.0; }).passed());
  EXPECT_FALSE(chiSquareTest(h, [](double x, double) { return 2.0 * x; }).passed());
}

// --- Cosine bounds. ----------------------------------------------------------------------

// atLeastCosOf answers c >= cos(a) to the bit. The hard cases are c within a few ulps of
// cos(a), where the bounds' margin decides whether cos is called: every c within 40 ulps
// either side of cosf(a), for a over [0, 1] (dense near 0, where the bounds are tight).
TEST(CosineBounds, AnswerAsCosDoesWithinUlpsOfTheBoundary) {
  int mismatches = 0, checked = 0;
  for (int i = 0; i <= 20000; ++i) {
    const float t = float(i) / 20000.0f, a = t * t;
    const float c0 = std::cos(a);
    float below = c0, above = c0;
    for (int k = 0; k <= 40; ++k) {
      for (const float c : {below, above}) {
        mismatches += atLeastCosOf(c, a) != (c >= std::cos(a));
        ++checked;
      }
      below = std::nextafter(below, -2.0f), above = std::nextafter(above, 2.0f);
    }
  }
  EXPECT_EQ(mismatches, 0) << "of " << checked;
  // Far from the boundary the bounds answer alone, either way.
  EXPECT_TRUE(atLeastCosOf(1.0f, 0.25f));
  EXPECT_FALSE(atLeastCosOf(0.9f, 0.25f));
}

// --- Random numbers. --------------------------------------------------------------------

TEST(Rng, UnitFloatNeverReachesOne) {
  EXPECT_LT(toUnitFloat(0xffffffffu), 1.0f);
  EXPECT_EQ(toUnitFloat(0u), 0.0f);
}

TEST(Rng, SameCountersSameNumbers) {
  const SampleCounters c{.pixel = 7, .eye = 1, .frame = 3, .sample = 2, .bounce = 4, .seed = 9};
  Sampler a = Sampler::make(c), b = Sampler::make(c);
  for (int i = 0; i < 16; ++i) EXPECT_EQ(a.next(), b.next());
  // Each counter changes the stream.
  for (uint32_t SampleCounters::*field :
       {&SampleCounters::pixel, &SampleCounters::eye, &SampleCounters::frame,
        &SampleCounters::sample, &SampleCounters::bounce, &SampleCounters::seed}) {
    SampleCounters d = c;
    d.*field += 1;
    EXPECT_NE(Sampler::make(d).key, Sampler::make(c).key);
  }
}

TEST(Rng, PathSamplerThenBounceIsMake) {
  // The path tracer hashes a path's counters once and each bounce from there; next() hashes
  // the key once per sampler. Both must leave every number as the stream defines it:
  // hashCombine(key, draw) itself (Random) or the shuffled Sobol point of the sample index
  // under that seed (Sobol).
  for (const SamplerKind kind : {SamplerKind::Random, SamplerKind::Sobol}) {
    const SampleCounters c{.pixel = 70,
                           .eye = 1,
                           .frame = 13,
                           .sample = 3,
                           .bounce = 0,
                           .seed = 5,
                           .samplesPerFrame = 4,
                           .kind = kind};
    const PathSampler path = PathSampler::make(c);
    EXPECT_EQ(path.index, kind == SamplerKind::Sobol ? 13u * 4u + 3u : 0u);
    for (uint32_t bounce = 0; bounce < 9; ++bounce) {
      SampleCounters d = c;
      d.bounce = bounce;
      Sampler a = Sampler::make(d), b = path.bounce(bounce);
      EXPECT_EQ(a.key, b.key);
      for (uint32_t dim = 0; dim < 8; ++dim) {
        const uint32_t bits = hashCombine(a.key, dim);
        const float expected = toUnitFloat(
            kind == SamplerKind::Random ? bits : shuffledSobol1D(c.sampleIndex(), bits));
        EXPECT_EQ(a.next(), expected);
        EXPECT_EQ(b.next(), expected);
      }
    }
  }
  Sampler zero;  // a default sampler draws as key 0 does
  EXPECT_EQ(zero.next(), toUnitFloat(hashCombine(0u, 0u)));
}

TEST(Rng, UniformOverPixelsAndDimensions) {
  // Pairs (dim 0, dim 1) over consecutive pixels on a 16 x 16 grid: tests uniformity and
  // the independence of two dimensions at once.
  Histogram h(16, 16);
  for (uint32_t p = 0; p < uint32_t(kSamples); ++p) {
    Sampler s = Sampler::make({.pixel = p, .frame = 5});
    h.add(s.next2());
  }
  const auto r = chiSquareTest(h, [](double, double) { return 1.0; });
  EXPECT_TRUE(r.passed()) << r.describe();
}

// --- Frames and warps. ------------------------------------------------------------------

TEST(OrthonormalBasis, OrthonormalForAllNormalsIncludingPoles) {
  // Duff et al. 2017 report max error ~1e-7 for unit float input; 1e-5 leaves room for
  // the input normal's own rounding.
  std::vector<glm::vec3> normals = {
      {0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}, glm::normalize(glm::vec3(1e-4f, 0, -1))};
  Sampler s = testSampler(2);
  for (int i = 0; i < 1000; ++i) normals.push_back(sampleUniformSphere(s.next2()));
  for (const glm::vec3& n : normals) {
    const Frame f = Frame::fromZ(n);
    EXPECT_NEAR(glm::length(f.x), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(f.y), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(f.x, f.y), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(f.x, n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(f.y, n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(glm::cross(f.x, f.y), n), 1.0f, 1e-5f) << "right-handed";
    const glm::vec3 v(0.3f, -0.5f, 0.81f);
    EXPECT_NEAR(glm::length(f.toWorld(f.toLocal(v)) - v), 0.0f, 1e-5f);
  }
}

// Directions in the (cos theta, phi) square: x = (1 + cos theta) / 2, y = phi / (2 pi);
// solid angle dw = dcos dphi = 4 pi dx dy.
glm::vec2 sphereCoords(const glm::vec3& w) {
  float phi = std::atan2(w.y, w.x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  return {0.5f * (1.0f + w.z), phi * kInv2Pi};
}
glm::vec3 sphereDirection(double x, double y) {
  const double z = 2.0 * x - 1.0, r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return glm::vec3(float(r * std::cos(2 * M_PI * y)), float(r * std::sin(2 * M_PI * y)), float(z));
}

template <class SampleFn, class PdfFn>
void expectDirectionsFollowPdf(SampleFn sample, PdfFn pdf, uint32_t seed) {
  Histogram h(20, 40);
  Sampler s = testSampler(seed);
  for (int i = 0; i < kSamples; ++i) h.add(sphereCoords(sample(s.next2())));
  const auto r =
      chiSquareTest(h, [&](double x, double y) { return 4.0 * M_PI * pdf(sphereDirection(x, y)); });
  EXPECT_TRUE(r.passed()) << r.describe();
}

TEST(Warps, CosineHemisphereChiSquare) {
  expectDirectionsFollowPdf(
      sampleCosineHemisphere, [](const glm::vec3& w) { return cosineHemispherePdf(w.z); }, 3);
}

TEST(Warps, UniformSphereChiSquare) {
  expectDirectionsFollowPdf(
      sampleUniformSphere, [](const glm::vec3&) { return uniformSpherePdf(); }, 4);
}

TEST(Warps, UniformConeChiSquare) {
  const float cosMax = std::cos(glm::radians(60.0f));
  expectDirectionsFollowPdf(
      [&](glm::vec2 u) { return sampleUniformCone(u, cosMax); },
      [&](const glm::vec3& w) { return w.z >= cosMax ? uniformConePdf(cosMax) : 0.0f; }, 5);
}

TEST(Warps, SamplesAreUnitLength) {
  Sampler s = testSampler(6);
  for (int i = 0; i < 1000; ++i) {
    const glm::vec2 u = s.next2();
    EXPECT_NEAR(glm::length(sampleCosineHemisphere(u)), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(sampleUniformSphere(u)), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(sampleUniformCone(u, 0.3f)), 1.0f, 1e-5f);
  }
  EXPECT_GE(sampleCosineHemisphere({0.5f, 0.5f}).z, 0.0f);
  EXPECT_GE(sampleCosineHemisphere({0.0f, 0.0f}).z, 0.0f);
}

TEST(PowerHeuristic, WeightsSumToOneAndSurviveHugePdfs) {
  EXPECT_FLOAT_EQ(powerHeuristic(1, 2.0f, 1, 1.0f) + powerHeuristic(1, 1.0f, 1, 2.0f), 1.0f);
  EXPECT_FLOAT_EQ(powerHeuristic(1, 2.0f, 1, 1.0f), 0.8f);  // 4 / (4 + 1)
  EXPECT_EQ(powerHeuristic(1, 0.0f, 1, 0.0f), 0.0f);
  EXPECT_EQ(powerHeuristic(1, 1e30f, 1, 1.0f), 1.0f);
  EXPECT_TRUE(isFinite(powerHeuristic(1, 1e-30f, 1, 1e30f)));
}

// --- Piecewise-constant distributions. --------------------------------------------------

TEST(Distribution1D, SamplesFollowTheFunctionAndSkipZeroCells) {
  const std::vector<float> f = {0.0f, 1.0f, 3.0f, 0.0f, 0.5f, 0.0f};
  const Distribution1D d(f);
  EXPECT_FLOAT_EQ(d.integral(), 4.5f / 6.0f);
  Histogram h(12, 1);  // two bins per cell: also checks uniformity inside a cell
  Sampler s = testSampler(7);
  for (int i = 0; i < kSamples; ++i) {
    const auto c = d.sampleContinuous(s.next());
    ASSERT_GT(f[c.index], 0.0f);
    ASSERT_LT(c.x, 1.0f);
    // The reported pdf is the density at x (exact: the same float division).
    ASSERT_EQ(c.pdf, d.pdf(c.x));
    h.add({c.x, 0.5f});
  }
  const auto r = chiSquareTest(h, [&](double x, double) { return d.pdf(float(x)); });
  EXPECT_TRUE(r.passed()) << r.describe();
  // Discrete: the pmf is f / sum f, and the extreme u values land on non-zero cells.
  EXPECT_FLOAT_EQ(d.sampleDiscrete(0.5f).pmf, 3.0f / 4.5f);
  EXPECT_EQ(d.sampleDiscrete(0.0f).index, 1);
  EXPECT_EQ(d.sampleDiscrete(kOneMinusEpsilon).index, 4);
  EXPECT_EQ(d.sampleContinuous(0.0f).index, 1);
}

// The constructor's cdf, recomputed as it does.
std::vector<float> referenceCdf(const std::vector<float>& f) {
  std::vector<float> func(f.size());
  double sum = 0.0;
  for (size_t i = 0; i < f.size(); ++i) {
    func[i] = f[i] > 0.0f ? std::min(f[i], std::numeric_limits<float>::max()) : 0.0f;
    sum += func[i];
  }
  if (sum == 0.0) {
    std::fill(func.begin(), func.end(), 1.0f);
    sum = double(f.size());
  }
  std::vector<float> cdf(f.size() + 1, 0.0f);
  double running = 0.0;
  for (size_t i = 0; i < f.size(); ++i) {
    running += func[i];
    cdf[i + 1] = float(running / sum);
  }
  cdf.back() = 1.0f;
  return cdf;
}

// The cell std::upper_bound finds on that cdf, clamped to the cells: what findCell
// returned before it had a guide table.
int upperBoundCell(const std::vector<float>& cdf, float u) {
  const int i = int(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin()) - 1;
  return std::clamp(i, 0, int(cdf.size()) - 2);
}

TEST(Distribution1D, GuidedSearchFindsTheCellsUpperBoundFinds) {
  // Exactly the same cell for every u: the guide table must not change a single sample.
  // Sizes below, at and above the guide's 256 cells; runs of zero cells; a spike that puts
  // many cells into one guide bin; u on every cdf value and its neighbours, and outside
  // [0, 1) (NaN, negative, 1 and above), where the full search runs.
  std::vector<std::vector<float>> functions = {
      {1.0f}, {0.0f, 2.0f}, {3.0f, 0.0f, 0.0f, 1.0f, 0.5f}};
  for (int n : {63, 64, 65, 255, 256, 257, 1000, 2048}) {
    std::vector<float> f(static_cast<size_t>(n), 0.0f);
    for (int i = 0; i < n; ++i) f[i] = (i % 7 == 3) ? 0.0f : 1.0f + float((i * 37) % 11);
    functions.push_back(f);
    f.assign(size_t(n), 1e-3f);
    f[size_t(n) / 3] = 1e6f;  // a spike: most of the mass in one cell
    for (int i = n / 2; i < n / 2 + n / 8; ++i) f[i] = 0.0f;
    functions.push_back(f);
  }
  Sampler s = testSampler(21);
  for (const std::vector<float>& f : functions) {
    const Distribution1D d(f);
    std::vector<float> us = {0.0f, kOneMinusEpsilon, 1.0f, 1.5f, -0.25f, -0.0f, std::nanf("")};
    for (int k = 0; k < 4000; ++k) us.push_back(s.next());
    const std::vector<float> cdf = referenceCdf(f);
    for (float edge : cdf) {  // the cell edges
      for (float u : {edge, std::nextafter(edge, 0.0f), std::nextafter(edge, 1.0f)})
        us.push_back(u);
    }
    for (int k = 1; k < 256; ++k) us.push_back(float(k) / 256.0f);  // the guide bins' edges
    for (float u : us) {
      const int expected = upperBoundCell(cdf, u);
      ASSERT_EQ(d.sampleDiscrete(u).index, expected) << "n " << f.size() << " u " << u;
      ASSERT_EQ(d.sampleContinuous(u).index, expected) << "n " << f.size() << " u " << u;
    }
  }
}

TEST(Distribution1D, AllZeroIsUniform) {
  const std::vector<float> f(4, 0.0f);
  const Distribution1D d(f);
  EXPECT_FLOAT_EQ(d.sampleContinuous(0.6f).x, 0.6f);
  EXPECT_FLOAT_EQ(d.sampleContinuous(0.6f).pdf, 1.0f);
}

TEST(Distribution1D, NegativeAndNanCountAsZero) {
  const std::vector<float> f = {-1.0f, std::nanf(""), 2.0f};
  const Distribution1D d(f);
  EXPECT_EQ(d.sampleContinuous(0.0f).index, 2);
  EXPECT_EQ(d.pdf(0.1f), 0.0f);
  EXPECT_FLOAT_EQ(d.pdf(0.9f), 3.0f);
  EXPECT_EQ(d.pdf(std::nanf("")), 0.0f);  // NaN x reads cell 0, no UB
}

TEST(Distribution2D, SamplesFollowTheFunction) {
  // 5 x 3 with a zero row and a hot cell; a 10 x 6 histogram also checks uniformity
  // within cells. Density = f / mean(f).
  const std::vector<float> f = {1, 2, 0, 1, 1,  //
                                0, 0, 0, 0, 0,  //
                                4, 1, 9, 1, 0.5f};
  const Distribution2D d(f, 5, 3);
  Histogram h(10, 6);
  Sampler s = testSampler(8);
  for (int i = 0; i < kSamples; ++i) {
    const auto c = d.sample(s.next2());
    ASSERT_GT(f[c.cell.y * 5 + c.cell.x], 0.0f);
    ASSERT_FLOAT_EQ(c.pdf, d.pdf(c.p));  // 1 ulp: one product vs the same product
    h.add(c.p);
  }
  const auto r = chiSquareTest(h, [&](double x, double y) { return d.pdf({float(x), float(y)}); });
  EXPECT_TRUE(r.passed()) << r.describe();
  const float mean = 20.5f / 15.0f;
  EXPECT_FLOAT_EQ(d.pdf({0.5f, 0.9f}), 9.0f / mean);
}

}  // namespace
}  // namespace photovr
