// The batched draws (trace/vertex_numbers.h) are the numbers a Sampler gives one by one, in
// shadeVertex's order: the batched tracer's SIMD stage may not change a single bit.
#include <gtest/gtest.h>

#include <vector>

#include "trace/vertex_numbers.h"

namespace photovr {
namespace {

// 'count' paths of distinct pixels and samples; 1037 is no multiple of the SIMD width, so
// the vector loops' remainders run too.
std::vector<PathSampler> paths(SamplerKind kind, size_t count) {
  std::vector<PathSampler> p;
  for (uint32_t i = 0; i < count; ++i) {
    SampleCounters c;
    c.pixel = i * 7919u;
    c.sample = i % 5;
    c.frame = i % 3;
    c.samplesPerFrame = 5;
    c.seed = 11;
    c.kind = kind;
    p.push_back(PathSampler::make(c));
  }
  return p;
}

// What shadeVertex drew before the stage existed: Sampler::next/next2 in its order.
VertexNumbers drawnOneByOne(const PathSampler& path, uint32_t depth, VertexDraws draws) {
  Sampler s = path.bounce(depth);
  VertexNumbers n;
  if (draws.lights) {
    n.lightPick = s.next();
    n.lightPoint = s.next2();
  }
  n.bsdf = s.next2();
  if (draws.roulette) n.roulette = s.next();
  return n;
}

void expectSame(const VertexNumbers& a, const VertexNumbers& b, size_t i) {
  // Bit equality: integer hashing and an exact int-to-float scaling, no rounding anywhere.
  EXPECT_EQ(a.lightPick, b.lightPick) << i;
  EXPECT_EQ(a.lightPoint, b.lightPoint) << i;
  EXPECT_EQ(a.bsdf, b.bsdf) << i;
  EXPECT_EQ(a.roulette, b.roulette) << i;
}

TEST(VertexNumbers, BatchedDrawsAreTheSamplersOwnNumbers) {
  for (SamplerKind kind : {SamplerKind::Sobol, SamplerKind::Random}) {
    const std::vector<PathSampler> p = paths(kind, 1037);
    std::vector<VertexNumbers> batch(p.size());
    for (uint32_t depth : {0u, 3u, 7u})
      for (VertexDraws draws : {VertexDraws{true, true}, VertexDraws{false, true},
                                VertexDraws{true, false}, VertexDraws{false, false}}) {
        drawBatchNumbers(p, depth, draws, batch);
        for (size_t i = 0; i < p.size(); ++i) {
          expectSame(batch[i], drawnOneByOne(p[i], depth, draws), i);
          expectSame(batch[i], drawVertexNumbers(p[i], depth, draws), i);
        }
      }
  }
}

TEST(VertexNumbers, DrawsThatAreNotMadeStayZero) {
  const std::vector<PathSampler> p = paths(SamplerKind::Sobol, 3);
  std::vector<VertexNumbers> batch(p.size());
  drawBatchNumbers(p, 0, {false, false}, batch);
  for (const VertexNumbers& n : batch) {
    EXPECT_EQ(n.lightPick, 0.0f);
    EXPECT_EQ(n.lightPoint, glm::vec2(0.0f));
    EXPECT_EQ(n.roulette, 0.0f);
    EXPECT_NE(n.bsdf, glm::vec2(0.0f));  // 2^-48 odds of a true zero pair
  }
}

}  // namespace
}  // namespace photovr
