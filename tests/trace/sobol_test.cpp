#include "core/sobol.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "tests/trace/chi_square.h"
#include "trace/rng.h"
#include "trace/sampling.h"

namespace photovr {
namespace {

using test::chiSquareTest;
using test::Histogram;
using Net = std::vector<glm::uvec2>;
using Points = std::vector<glm::dvec2>;

// Test inputs: the i-th value of a hashed stream named by `tag`.
uint32_t testBits(uint32_t tag, uint32_t i) {
  return hashCombine(tag, i);
}

// The top `bits` digits of a 32-bit binary fraction: the index of the elementary interval
// of width 2^-bits it lies in.
uint32_t top(uint32_t v, int bits) {
  return bits == 0 ? 0u : v >> (32 - bits);
}

// A sampler's float back to its 32-bit fraction: toUnitFloat keeps the top 24 bits exactly.
uint32_t fractionBits(float u) {
  return uint32_t(u * 0x1p24f) << 8;
}

// --- Nets. -------------------------------------------------------------------------------

// The number of elementary intervals of area 2^-k (shapes 2^-a x 2^-(k-a), a = 0..k) that do
// not hold exactly one of the 2^k points: zero iff they form a (0, k, 2)-net in base 2.
int netDefects(const Net& p, int k) {
  std::vector<int> count(size_t(1) << k);
  int defects = 0;
  for (int a = 0; a <= k; ++a) {
    std::fill(count.begin(), count.end(), 0);
    for (const glm::uvec2& q : p) ++count[(top(q.x, a) << (k - a)) | top(q.y, k - a)];
    defects += int(std::count_if(count.begin(), count.end(), [](int c) { return c != 1; }));
  }
  return defects;
}

// Points first .. first + n - 1 of a generator of 32-bit pairs.
Net netPoints(const std::function<glm::uvec2(uint32_t)>& gen, uint32_t first, uint32_t n) {
  Net p(n);
  for (uint32_t i = 0; i < n; ++i) p[i] = gen(first + i);
  return p;
}

// Every aligned block of 2^k indices, k = 0..12, the first and three later ones (block 3,
// and one far out where the top index bits are set), must be a net: a (0, 2)-sequence.
void expectNetsInEveryBlock(const std::function<glm::uvec2(uint32_t)>& gen) {
  for (int k = 0; k <= 12; ++k) {
    const uint32_t n = 1u << k;
    for (uint32_t block : {0u, 1u, 3u, 0x7654u}) {
      ASSERT_EQ(netDefects(netPoints(gen, block * n, n), k), 0) << "k " << k << " block " << block;
    }
  }
}

// Sobol's second dimension from its definition, not from sobol.h's recurrence: the generator
// matrix of the polynomial x + 1 is Pascal's triangle mod 2, row i of column j set iff
// C(j, i) is odd, i.e. (by Lucas's theorem) iff i's bits are a subset of j's.
uint32_t naiveSobolDimension1(uint32_t index) {
  uint32_t v = 0;
  for (uint32_t j = 0; j < 32; ++j) {
    if (!(index >> j & 1u)) continue;
    for (uint32_t i = 0; i <= j; ++i)
      if ((i & j) == i) v ^= 1u << (31 - i);
  }
  return v;
}

TEST(Sobol, DimensionOneMatchesItsDefinition) {
  // The tabulated direction numbers m_1..m_8 of Sobol's second dimension (v_j = m_j / 2^j =
  // 1/2, 3/4, 5/8, 15/16, ...): the columns m_j 2^(32-j), i.e. the points of indices 2^(j-1).
  const uint32_t m[] = {1, 3, 5, 15, 17, 51, 85, 255};
  for (uint32_t j = 1; j <= 8; ++j) EXPECT_EQ(sobolDimension1(1u << (j - 1)), m[j - 1] << (32 - j));
  for (uint32_t i = 0; i < 4096; ++i) {
    const uint32_t index = i < 2048 ? i : testBits(1, i);
    ASSERT_EQ(sobolDimension1(index), naiveSobolDimension1(index)) << index;
  }
}

TEST(Sobol, UnscrambledPointsAreNets) {
  expectNetsInEveryBlock(
      [](uint32_t i) { return glm::uvec2(sobolDimension0(i), sobolDimension1(i)); });
}

TEST(Sobol, ScrambledPointsAreNets) {
  for (uint32_t seed : {0u, 1u, 0xdeadbeefu})
    expectNetsInEveryBlock([&](uint32_t i) { return scrambledSobol2D(i, seed); });
}

TEST(Sobol, ShuffledPointsAreNets) {
  for (uint32_t seed : {7u, 0x9e3779b9u})
    expectNetsInEveryBlock([&](uint32_t i) { return shuffledSobol2D(i, seed); });
}

TEST(Sobol, SamplerPairsAreNetsOverTheSampleIndex) {
  // As the renderer draws them: next2 of a fresh Sobol sampler per sample index, the index
  // spanning frames (frame * n + sample, n = 4), through the 24-bit floats.
  expectNetsInEveryBlock([](uint32_t i) {
    Sampler s = Sampler::make({.pixel = 321,
                               .frame = i / 4,
                               .sample = i % 4,
                               .seed = 5,
                               .samplesPerFrame = 4,
                               .kind = SamplerKind::Sobol});
    s.next();  // the pair is the sampler's second draw
    const glm::vec2 u = s.next2();
    return glm::uvec2(fractionBits(u.x), fractionBits(u.y));
  });
}

TEST(Sobol, NetTestRejectsPointSetsThatAreNotNets) {
  // Negative controls for netDefects, at k = 8: the diagonal (dimension 0 twice: 2 x 2 cells
  // off the diagonal are empty), and two independent padded 1D draws (each axis stratified,
  // the pairing pseudo-random: with 256 points some 16 x 16 cell is empty with near certainty).
  auto diagonal = [](uint32_t i) { return glm::uvec2(sobolDimension0(i), sobolDimension0(i)); };
  auto padded = [](uint32_t i) { return glm::uvec2(shuffledSobol1D(i, 1), shuffledSobol1D(i, 2)); };
  EXPECT_GT(netDefects(netPoints(diagonal, 0, 256), 8), 0);
  EXPECT_GT(netDefects(netPoints(padded, 0, 256), 8), 0);
}

// Whether the top k digits of the n = 2^k values are all different: one value in each of
// the n intervals [i / n, (i + 1) / n).
bool stratified1D(const std::function<uint32_t(uint32_t)>& gen, uint32_t first, int k) {
  std::vector<bool> seen(size_t(1) << k, false);
  for (uint32_t i = 0; i < (1u << k); ++i) {
    const uint32_t cell = top(gen(first + i), k);
    if (seen[cell]) return false;
    seen[cell] = true;
  }
  return true;
}

TEST(Sobol, ShuffledOneDimensionalDrawsAreStratified) {
  auto shuffled = [](uint32_t i) { return shuffledSobol1D(i, 0x1234567u); };
  auto sampler = [](uint32_t i) {
    Sampler s = Sampler::make({.pixel = 9,
                               .sample = i,
                               .seed = 2,
                               .samplesPerFrame = 1u << 12,
                               .kind = SamplerKind::Sobol});
    return fractionBits(s.next());
  };
  for (int k = 0; k <= 12; ++k) {
    for (uint32_t block : {0u, 3u, 0x7654u}) {
      EXPECT_TRUE(stratified1D(shuffled, block << k, k)) << "k " << k << " block " << block;
      EXPECT_TRUE(stratified1D(sampler, block << k, k)) << "k " << k << " block " << block;
    }
  }
  // Negative control: 64 values of a hash leave some of 64 intervals empty (all filled has
  // probability 64! / 64^64 ~ 1e-27).
  EXPECT_FALSE(stratified1D([](uint32_t i) { return testBits(3, i); }, 0, 6));
}

// --- The Owen scramble. -----------------------------------------------------------------

uint32_t naiveReverseBits(uint32_t v) {
  uint32_t r = 0;
  for (int i = 0; i < 32; ++i) r |= (v >> i & 1u) << (31 - i);
  return r;
}

TEST(Sobol, ReverseBitsIsTheNaiveLoopAndAnInvolution) {
  EXPECT_EQ(reverseBits(1u), 0x80000000u);
  EXPECT_EQ(reverseBits(0x0000ffffu), 0xffff0000u);
  for (uint32_t i = 0; i < 10000; ++i) {
    const uint32_t v = i < 64 ? (i < 32 ? 1u << i : ~(1u << (i - 32))) : testBits(4, i);
    ASSERT_EQ(reverseBits(v), naiveReverseBits(v)) << v;
    ASSERT_EQ(reverseBits(reverseBits(v)), v) << v;
  }
}

// How many single-digit flips of v break nesting: flipping digit p (bit p) of the input must
// flip output bit p and leave every bit above it (the digits before it) alone.
int nestingViolations(const std::function<uint32_t(uint32_t)>& scramble, uint32_t v) {
  int violations = 0;
  for (int p = 0; p < 32; ++p) violations += ((scramble(v ^ (1u << p)) ^ scramble(v)) >> p) != 1u;
  return violations;
}

TEST(Sobol, OwenScrambleIsNested) {
  for (uint32_t i = 0; i < 500; ++i) {
    const uint32_t v = testBits(5, i), seed = i < 4 ? i : testBits(6, i);
    ASSERT_EQ(nestingViolations([&](uint32_t x) { return owenScramble(x, seed); }, v), 0)
        << "v " << v << " seed " << seed;
  }
  // Negative control: a hash of the whole word changes the leading digits.
  EXPECT_GT(nestingViolations([](uint32_t x) { return pcgHash(x); }, 12345u), 16);
}

TEST(Sobol, OwenScramblePermutesEveryPrefixLength) {
  // The top k digits of the output are a bijection of the top k of the input, whatever the
  // digits below (random here): each of the 2^k prefixes lands on a different one.
  for (uint32_t seed : {0u, 3u, 0x80000000u, 0xcafef00du}) {
    for (int k = 1; k <= 12; ++k) {
      auto gen = [&](uint32_t prefix) {
        const uint32_t low = testBits(7, prefix) >> k;
        return owenScramble(prefix << (32 - k) | low, seed);
      };
      EXPECT_TRUE(stratified1D(gen, 0, k)) << "k " << k << " seed " << seed;
    }
  }
}

// --- Star discrepancy. ------------------------------------------------------------------

// The exact star discrepancy of points in [0,1)^2, sup over anchored boxes [0,a) x [0,b) of
// |count / N - ab|. The count is constant between the points' coordinates, so the sup is a
// limit at a corner (a, b), a in {x_i} u {1}, b in {y_j} u {1}: from below, ab minus the
// points strictly inside; from above, the points with x <= a and y <= b minus ab
// (Niederreiter 1972). Sweeping a in x order with per-y-rank counts of the points left of a,
// one prefix sum over the y ranks gives both counts for every b: O(N^2).
double starDiscrepancy(const Points& p) {
  std::vector<double> xs = {1.0}, ys = {1.0};
  for (const glm::dvec2& q : p) {
    xs.push_back(q.x);
    ys.push_back(q.y);
  }
  for (std::vector<double>* v : {&xs, &ys}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  auto rank = [](const std::vector<double>& v, double x) {
    return size_t(std::lower_bound(v.begin(), v.end(), x) - v.begin());
  };
  std::vector<std::vector<size_t>> yRanksAtX(xs.size());
  for (const glm::dvec2& q : p) yRanksAtX[rank(xs, q.x)].push_back(rank(ys, q.y));
  std::vector<int> left(ys.size(), 0), at(ys.size(), 0);  // x < a, x == a; by y rank
  const double n = double(p.size());
  double d = 0.0;
  for (size_t ia = 0; ia < xs.size(); ++ia) {
    for (size_t ry : yRanksAtX[ia]) ++at[ry];
    int open = 0, closed = 0;
    for (size_t ib = 0; ib < ys.size(); ++ib) {
      closed += left[ib] + at[ib];
      const double area = xs[ia] * ys[ib];
      d = std::max({d, area - open / n, closed / n - area});
      open += left[ib];
    }
    for (size_t ry : yRanksAtX[ia]) {
      ++left[ry];
      at[ry] = 0;
    }
  }
  return d;
}

// The same by counting the points for every corner: O(N^3).
double bruteForceStarDiscrepancy(const Points& p) {
  std::vector<double> xs = {1.0}, ys = {1.0};
  for (const glm::dvec2& q : p) {
    xs.push_back(q.x);
    ys.push_back(q.y);
  }
  double d = 0.0;
  for (double a : xs)
    for (double b : ys) {
      int open = 0, closed = 0;
      for (const glm::dvec2& q : p) {
        open += q.x < a && q.y < b;
        closed += q.x <= a && q.y <= b;
      }
      d = std::max({d, a * b - open / double(p.size()), closed / double(p.size()) - a * b});
    }
  return d;
}

TEST(SobolDiscrepancy, StarDiscrepancyMatchesClosedFormsAndBruteForce) {
  // One point at the centre: the closed box [0, 1/2]^2 holds all of it, area 1/4.
  EXPECT_DOUBLE_EQ(starDiscrepancy({{0.5, 0.5}}), 0.75);
  // N points (i / N, i / N), N even: the box [0, a]^2 holds floor(aN) + 1 of them, worst at
  // a = 1/2: 1/2 + 1/N - 1/4.
  Points diagonal;
  for (int i = 0; i < 64; ++i) diagonal.push_back(glm::dvec2(i / 64.0));
  EXPECT_DOUBLE_EQ(starDiscrepancy(diagonal), 0.25 + 1.0 / 64.0);
  // Random points, with ties on a coarse grid and without.
  for (double grid : {8.0, 0.0}) {
    Points p;
    for (uint32_t i = 0; i < 60; ++i) {
      glm::dvec2 q(testBits(8, i) * 0x1p-32, testBits(9, i) * 0x1p-32);
      if (grid > 0.0) q = glm::floor(q * grid) / grid;
      p.push_back(q);
    }
    EXPECT_DOUBLE_EQ(starDiscrepancy(p), bruteForceStarDiscrepancy(p)) << "grid " << grid;
  }
}

enum class Over { Samples, Frames };  // the index as the sample (n per frame) or the frame

SampleCounters counters(uint32_t pixel, uint32_t index, uint32_t n, Over over, SamplerKind kind) {
  SampleCounters c{.pixel = pixel, .eye = 1, .seed = 77, .kind = kind};
  if (over == Over::Samples) {
    c.sample = index;
    c.samplesPerFrame = n;
  } else {
    c.frame = index;
  }
  return c;
}

Points drawPoints(uint32_t n, const std::function<glm::vec2(uint32_t)>& draw) {
  Points p(n);
  for (uint32_t i = 0; i < n; ++i) p[i] = glm::dvec2(draw(i));
  return p;
}

// next2 of pixel `pixel` over indices 0..n-1.
Points pairs(SamplerKind kind, uint32_t pixel, uint32_t n, Over over) {
  return drawPoints(
      n, [&](uint32_t i) { return Sampler::make(counters(pixel, i, n, over, kind)).next2(); });
}

struct RandomDiscrepancy {
  double min = std::numeric_limits<double>::infinity(), mean = 0.0;
};

// Of random points (Random sampler, next2 over the sample index) for 8 pixels.
constexpr int kReplicates = 8;
RandomDiscrepancy randomDiscrepancy(uint32_t n) {
  RandomDiscrepancy r;
  for (uint32_t pixel = 0; pixel < kReplicates; ++pixel) {
    const double d = starDiscrepancy(pairs(SamplerKind::Random, pixel, n, Over::Samples));
    r.min = std::min(r.min, d);
    r.mean += d / kReplicates;
  }
  return r;
}

TEST(SobolDiscrepancy, PairsAreFarBelowRandomAndWithinTheNetBound) {
  // Any (0, m, 2)-net in base 2 has N D* <= m + 1: an anchored box contains the union of
  // m elementary-interval columns (a's binary digits, each column's height b truncated to
  // its interval's grain) and is contained in the same union rounded up; each holds exactly
  // N times its area, and truncation costs < 2^-m of area per digit plus 2^-m for a's own
  // truncation. Random points have D* ~ 1/sqrt(N), far above log N / N; their minimum over
  // 8 sets must still be above every Sobol net's. The index as the sample (n per frame) and
  // as the frame (1 per frame): the same index, so the same net.
  for (uint32_t m : {6u, 8u, 10u}) {
    const uint32_t n = 1u << m;
    const RandomDiscrepancy random = randomDiscrepancy(n);
    for (Over over : {Over::Samples, Over::Frames}) {
      const double d = starDiscrepancy(pairs(SamplerKind::Sobol, 3, n, over));
      EXPECT_LE(d, (m + 1.0) / n) << "n " << n;
      EXPECT_LT(d, random.min) << "n " << n;
    }
  }
}

// Two 1D draws per index: the first two of one sampler, or the first of bounces 0 and 1.
glm::vec2 paddedPair(const SampleCounters& c, bool twoBounces) {
  Sampler s = Sampler::make(c);
  const float a = s.next();
  if (!twoBounces) return {a, s.next()};
  SampleCounters d = c;
  d.bounce = 1;
  return {a, Sampler::make(d).next()};
}

double meanPaddedDiscrepancy(uint32_t n, bool twoBounces) {
  double mean = 0.0;
  for (uint32_t pixel = 0; pixel < kReplicates; ++pixel) {
    const Over over = pixel % 2 ? Over::Frames : Over::Samples;
    auto draw = [&](uint32_t i) {
      return paddedPair(counters(pixel, i, n, over, SamplerKind::Sobol), twoBounces);
    };
    mean += starDiscrepancy(drawPoints(n, draw)) / kReplicates;
  }
  return mean;
}

TEST(SobolDiscrepancy, PaddedOneDimensionalPairsAreBelowRandomOnAverage) {
  // Two 1D draws: of one sampler, and of bounces 0 and 1; the mean over 8 pixels (half over
  // samples, half over frames). Each axis is stratified and the pairing pseudo-random, like a
  // Latin hypercube sample: a box's count has variance N ab (1 - a)(1 - b), at most N / 16, where
  // random points' N ab (1 - ab) reaches N / 4, so the largest local deviations halve
  // (measured: 0.43 to 0.58 of random's). Below 3/4 of random's mean leaves room for the
  // ~10 % noise of each 8-set mean; draws that were not stratified would give ~1, two draws
  // sharing a seed the diagonal, 1/4 + 1/N.
  for (uint32_t n : {64u, 256u, 1024u}) {
    const double random = randomDiscrepancy(n).mean;
    EXPECT_LT(meanPaddedDiscrepancy(n, false), 0.75 * random) << "n " << n;
    EXPECT_LT(meanPaddedDiscrepancy(n, true), 0.75 * random) << "n " << n;
  }
}

// --- Estimates over many scrambles. -----------------------------------------------------

// 2000 pixels (independent scrambles) of 256 samples each: the mean of the 2000 estimates is
// known to its standard error sd / sqrt(2000), their variance to a relative sd of
// sqrt(2 / 1999) = 3.2 % (near-normal estimates).
constexpr uint32_t kPixels = 2000;
constexpr uint32_t kSamplesPerPixel = 256;

// The quarter disc of radius 0.8 (discontinuous) and x y e^x (smooth), with their integrals
// over [0,1]^2, their variances under one uniform point, and the variances of their additive
// parts, the main effects E[f | x] + E[f | y] (what stratifying each axis alone removes).
// Disc: p = pi 0.64 / 4, variance p (1 - p), E[f | x] = sqrt(0.64 - x^2) for x < 0.8, whose
// square integrates to 0.64 * 0.8 - 0.8^3 / 3. Smooth: the integral of x e^x is 1, of
// x^2 e^2x (e^2 - 1) / 4, so the mean is 1/2, E[f | x] = x e^x / 2, E[f | y] = y.
struct Integrand {
  std::function<double(glm::dvec2)> f;
  double integral, variance, additiveVariance;
};
const double kDiscArea = M_PI * 0.64 / 4.0;
const double kDiscVariance = kDiscArea * (1.0 - kDiscArea);
const double kDiscAdditive = 2.0 * (0.64 * 0.8 - 0.8 * 0.8 * 0.8 / 3.0 - kDiscArea * kDiscArea);
const Integrand kDisc{[](glm::dvec2 p) { return p.x * p.x + p.y * p.y < 0.64 ? 1.0 : 0.0; },
                      kDiscArea, kDiscVariance, kDiscAdditive};
const double kXSquaredE2X = (std::exp(2.0) - 1.0) / 4.0;
const Integrand kSmooth{[](glm::dvec2 p) { return p.x * p.y * std::exp(p.x); }, 0.5,
                        kXSquaredE2X / 3.0 - 0.25, (kXSquaredE2X - 1.0) / 4.0 + 1.0 / 12.0};

struct Moments {
  double mean = 0.0, variance = 0.0;  // of the per-pixel estimates
  double standardError() const { return std::sqrt(variance / kPixels); }
};

using Draw = std::function<glm::vec2(uint32_t pixel, uint32_t index)>;

Moments estimates(const Draw& draw, const Integrand& g) {
  std::vector<double> e(kPixels, 0.0);
  for (uint32_t pixel = 0; pixel < kPixels; ++pixel) {
    for (uint32_t i = 0; i < kSamplesPerPixel; ++i) e[pixel] += g.f(glm::dvec2(draw(pixel, i)));
    e[pixel] /= kSamplesPerPixel;
  }
  Moments m;
  for (double v : e) m.mean += v / kPixels;
  for (double v : e) m.variance += (v - m.mean) * (v - m.mean) / (kPixels - 1);
  return m;
}

Sampler estimateSampler(uint32_t pixel, uint32_t i, SamplerKind kind) {
  return Sampler::make(counters(pixel, i, kSamplesPerPixel, Over::Samples, kind));
}
const Draw kSobol2D = [](uint32_t pixel, uint32_t i) {
  return estimateSampler(pixel, i, SamplerKind::Sobol).next2();
};
const Draw kSobolPadded = [](uint32_t pixel, uint32_t i) {
  return paddedPair(counters(pixel, i, kSamplesPerPixel, Over::Samples, SamplerKind::Sobol), false);
};
// The pixel positions' sequence, one scramble seed per pixel.
const Draw kScrambled2D = [](uint32_t pixel, uint32_t i) {
  const glm::uvec2 p = scrambledSobol2D(i, testBits(12, pixel));
  return glm::vec2(toUnitFloat(p.x), toUnitFloat(p.y));
};
const Draw kRandom = [](uint32_t pixel, uint32_t i) {
  return estimateSampler(pixel, i, SamplerKind::Random).next2();
};

TEST(SobolEstimates, AreUnbiased) {
  // Each scrambled point is uniform, so every estimate is unbiased: the mean over 2000
  // scrambles is within 4.5 of its standard errors of the integral (a false alarm below
  // 1e-5 per check). The 24-bit floats truncate, a bias < |grad f| 2^-25 < 3e-7, under 1/30
  // of the smallest standard error here (9e-6). A scrambling that did not randomize would have
  // standard error 0 and fail.
  for (const Integrand* g : {&kDisc, &kSmooth}) {
    for (const Draw* draw : {&kSobol2D, &kScrambled2D, &kSobolPadded}) {
      const Moments m = estimates(*draw, *g);
      EXPECT_GT(m.standardError(), 0.0);
      EXPECT_NEAR(m.mean, g->integral, 4.5 * m.standardError());
    }
  }
}

// The variance of a 256-point estimate relative to that of 256 independent uniform points.
double varianceRatio(const Draw& draw, const Integrand& g) {
  return estimates(draw, g).variance / (g.variance / kSamplesPerPixel);
}

// The sample variance of 2000 near-normal estimates has relative sd sqrt(2 / 1999): 4.5 of it.
constexpr double kVarianceTolerance = 0.143;

TEST(SobolEstimates, VarianceFarBelowRandom) {
  // The reference itself: Random's estimates have the variance of independent points.
  EXPECT_NEAR(varianceRatio(kRandom, kDisc), 1.0, kVarianceTolerance);
  // Owen-scrambled nets: for an integrand with a smooth edge, variance O(N^-1.5), as for
  // stratified sampling (Mitchell 1996, "Consequences of stratified sampling in graphics":
  // the edge crosses ~sqrt(N) of N cells, each adding ~1/N^2), i.e. ~N^-0.5 = 1/16 of Monte
  // Carlo's at N = 256: 1/4 leaves a constant 4. For a smooth integrand O(N^-3 log N) (Owen
  // 1997, "Scrambled net variance for integrals of smooth functions"): relative ~log2 N / N^2
  // = 1.2e-4; 1e-3 leaves a constant 8, and is below the ~1/N = 4e-3 that a randomization
  // without nesting (a random digital shift) gives.
  for (const Draw* draw : {&kSobol2D, &kScrambled2D}) {
    EXPECT_LT(varianceRatio(*draw, kDisc), 0.25);
    EXPECT_LT(varianceRatio(*draw, kSmooth), 1e-3);
  }
  // Two padded 1D draws: each axis stratified removes the additive part (Owen 1992, "A central
  // limit theorem for Latin hypercube sampling"); a uniformly random pairing would leave the
  // rest, (variance - additive) / N. The nested shuffle pairs indices 2j and 2j + 1 into
  // opposite halves of both axes, which doubles the variance of the coarsest interaction, so
  // allow twice that, plus the estimate's tolerance: still far below Monte Carlo's 1.
  for (const Integrand* g : {&kDisc, &kSmooth}) {
    const double residual = 1.0 - g->additiveVariance / g->variance;
    EXPECT_LT(varianceRatio(kSobolPadded, *g), 2.0 * residual * (1.0 + kVarianceTolerance))
        << "integral " << g->integral << " residual " << residual;
  }
}

// --- Counter-based draws. ---------------------------------------------------------------

// Every draw's bits, four next() and four next2(), interleaved.
std::vector<float> drawAll(Sampler s) {
  std::vector<float> v;
  for (int i = 0; i < 4; ++i) {
    v.push_back(s.next());
    const glm::vec2 u = s.next2();
    v.insert(v.end(), {u.x, u.y});
  }
  return v;
}

SampleCounters sobolCounters(uint32_t i) {
  return {.pixel = testBits(10, i) % 100000,
          .eye = i % 2,
          .frame = testBits(11, i) % 5000,
          .sample = i % 8,
          .bounce = i % 6,
          .seed = i % 3,
          .samplesPerFrame = 8,
          .kind = SamplerKind::Sobol};
}

TEST(SobolSampler, SameCountersSameBitsAndTheDrawsAreTheSequencesPoints) {
  for (uint32_t i = 0; i < 200; ++i) {
    const SampleCounters c = sobolCounters(i);
    const Sampler a = Sampler::make(c), b = PathSampler::make(c).bounce(c.bounce);
    EXPECT_EQ(drawAll(a), drawAll(Sampler::make(c)));
    EXPECT_EQ(drawAll(a), drawAll(b));
    EXPECT_EQ(b.index, c.sampleIndex());
    // Draw d is the sample index's point under seed hash(key, d); next2 takes one draw.
    Sampler s = a;
    EXPECT_EQ(s.next(), toUnitFloat(shuffledSobol1D(c.sampleIndex(), hashCombine(a.key, 0))));
    const glm::uvec2 p = shuffledSobol2D(c.sampleIndex(), hashCombine(a.key, 1));
    EXPECT_EQ(s.next2(), glm::vec2(toUnitFloat(p.x), toUnitFloat(p.y)));
    EXPECT_EQ(s.dim, 2u);
  }
}

TEST(SobolSampler, IndexIsFrameTimesSamplesPerFramePlusSample) {
  // Only the index frame * n + sample counts: the key names neither, so frame f, sample s of
  // n equals frame 0, sample fn + s and frame fn + s of 1 sample per frame.
  for (uint32_t i = 0; i < 200; ++i) {
    const SampleCounters c = sobolCounters(i);
    SampleCounters asSample = c, asFrame = c;
    asSample.frame = 0;
    asSample.sample = c.sampleIndex();
    asFrame.frame = c.sampleIndex();
    asFrame.sample = 0;
    asFrame.samplesPerFrame = 1;
    EXPECT_EQ(drawAll(Sampler::make(c)), drawAll(Sampler::make(asSample)));
    EXPECT_EQ(drawAll(Sampler::make(c)), drawAll(Sampler::make(asFrame)));
  }
}

TEST(SobolSampler, BounceDrawsDoNotDependOnEarlierBounces) {
  // A path makes a fresh sampler per bounce: bounce 1's numbers are the same whether bounce 0
  // drew 0 or 9 numbers, and they are not bounce 0's continued.
  const SampleCounters c = sobolCounters(7);
  const PathSampler path = PathSampler::make(c);
  const std::vector<float> bounce1 = drawAll(path.bounce(1));
  for (int consumed = 0; consumed < 10; ++consumed) {
    Sampler b0 = path.bounce(0);
    for (int k = 0; k < consumed; ++k) b0.next();
    EXPECT_EQ(drawAll(path.bounce(1)), bounce1);
    EXPECT_NE(drawAll(b0), bounce1);
  }
}

TEST(SobolSampler, PixelsAreIndependentScrambles) {
  // Neighbouring pixels at one index: their draws are uncorrelated over 4096 pixel pairs,
  // |r| below 4.5 / sqrt(4096) (r's sd for independent variables is 1 / sqrt(n)), and two
  // pixels' 24-bit draws coincide with probability 2^-24: none of 4096 pairs x 3 indices.
  constexpr uint32_t kPairs = 4096;
  for (uint32_t index : {0u, 1u, 1000u}) {
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    int equal = 0;
    for (uint32_t p = 0; p < kPairs; ++p) {
      const auto c = counters(p, index, 1024, Over::Samples, SamplerKind::Sobol);
      auto d = c;
      d.pixel = p + 1;
      const double x = Sampler::make(c).next(), y = Sampler::make(d).next();
      equal += x == y;
      sx += x;
      sy += y;
      sxx += x * x;
      syy += y * y;
      sxy += x * y;
    }
    const double n = kPairs, cov = sxy / n - sx * sy / (n * n);
    const double r = cov / std::sqrt((sxx / n - sx * sx / (n * n)) * (syy / n - sy * sy / (n * n)));
    EXPECT_LT(std::abs(r), 4.5 / std::sqrt(n)) << "index " << index;
    EXPECT_EQ(equal, 0) << "index " << index;
  }
}

// --- Chi-square with Sobol samples. -----------------------------------------------------

// Directions in the (cos theta, phi) square, as sampling_test.cpp's: x = (1 + cos theta) / 2,
// y = phi / (2 pi); solid angle dw = 4 pi dx dy.
glm::vec2 sphereCoords(const glm::vec3& w) {
  float phi = std::atan2(w.y, w.x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  return {0.5f * (1.0f + w.z), phi * kInv2Pi};
}
double cosThetaAt(double x) {
  return 2.0 * x - 1.0;
}

TEST(SobolChiSquare, CosineHemisphereWithSobolSamples) {
  // 2^17 indices of one pixel, one sampler each (a sampler's successive draws are independent
  // scrambles of one index, not a sequence: the stratification is over the index), 20 x 40
  // cells as Warps.CosineHemisphereChiSquare. The points are a net, filling the cells more
  // evenly than independent ones: the statistic, ~chi-square(dof) for those (mean dof, sd
  // sqrt(2 dof)), must fall below dof / 2, sqrt(dof / 8) ~ 7 sd below the mean. A wrong
  // density still rejects: the uniform hemisphere, and cos^1.2 (the exponent 20 % off).
  Histogram h(20, 40);
  for (uint32_t i = 0; i < (1u << 17); ++i) {
    const auto c = counters(42, i, 1u << 17, Over::Samples, SamplerKind::Sobol);
    h.add(sphereCoords(sampleCosineHemisphere(Sampler::make(c).next2())));
  }
  auto lobe = [](double exponent) {
    return [exponent](double x, double) {
      const double z = cosThetaAt(x);
      return z > 0.0 ? 4.0 * M_PI * (exponent + 1.0) * std::pow(z, exponent) / (2.0 * M_PI) : 0.0;
    };
  };
  const auto r = chiSquareTest(h, lobe(1.0));
  EXPECT_TRUE(r.passed()) << r.describe();
  EXPECT_LT(r.statistic, 0.5 * r.dof) << r.describe();
  EXPECT_FALSE(chiSquareTest(h, lobe(0.0)).passed());
  EXPECT_FALSE(chiSquareTest(h, lobe(1.2)).passed());
}

}  // namespace
}  // namespace photovr
