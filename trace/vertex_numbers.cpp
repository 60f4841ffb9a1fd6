#include "trace/vertex_numbers.h"

#include <cassert>
#include <vector>

namespace photovr {

VertexNumbers drawVertexNumbers(const PathSampler& path, uint32_t depth, VertexDraws draws) {
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

namespace {

// Structure-of-arrays scratch of one batch: each loop below runs over one array at a time,
// which GCC vectorises (pcgHash's per-lane shift, bswap and the Sobol table lookups need
// AVX2: vpsrlvd, vpshufb, vpgatherdd; the "default" clone is the scalar code).
struct DrawLanes {
  std::vector<uint32_t> hashedKey, index, bits, x, y;
};

#define PHOTOVR_SIMD_CLONES __attribute__((target_clones("avx2", "default")))

// bits[i] = the hash Sampler::next/next2 makes for draw 'dim' of lane i.
PHOTOVR_SIMD_CLONES void drawBits(const uint32_t* __restrict hashedKey, uint32_t dim,
                                  uint32_t* __restrict bits, size_t n) {
  for (size_t i = 0; i < n; ++i) bits[i] = pcgHash(dim + hashedKey[i]);
}

PHOTOVR_SIMD_CLONES void sobol1D(const uint32_t* __restrict index, const uint32_t* __restrict bits,
                                 uint32_t* __restrict x, size_t n) {
  for (size_t i = 0; i < n; ++i) x[i] = shuffledSobol1D(index[i], bits[i]);
}

PHOTOVR_SIMD_CLONES void sobol2D(const uint32_t* __restrict index, const uint32_t* __restrict bits,
                                 uint32_t* __restrict x, uint32_t* __restrict y, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    const glm::uvec2 p = shuffledSobol2D(index[i], bits[i]);
    x[i] = p.x;
    y[i] = p.y;
  }
}

// Lane i's 1D draw 'dim' into x[i] (as Sampler::next).
void draw1D(DrawLanes& l, SamplerKind kind, uint32_t dim, size_t n) {
  drawBits(l.hashedKey.data(), dim, l.x.data(), n);
  if (kind == SamplerKind::Sobol) {
    l.bits.swap(l.x);
    sobol1D(l.index.data(), l.bits.data(), l.x.data(), n);
  }
}

// Lane i's 2D draw starting at 'dim' into x[i], y[i]; returns the next free dimension.
uint32_t draw2D(DrawLanes& l, SamplerKind kind, uint32_t dim, size_t n) {
  if (kind == SamplerKind::Random) {
    drawBits(l.hashedKey.data(), dim, l.x.data(), n);
    drawBits(l.hashedKey.data(), dim + 1, l.y.data(), n);
    return dim + 2;
  }
  drawBits(l.hashedKey.data(), dim, l.bits.data(), n);
  sobol2D(l.index.data(), l.bits.data(), l.x.data(), l.y.data(), n);
  return dim + 1;
}

}  // namespace

void drawBatchNumbers(std::span<const PathSampler> paths, uint32_t depth, VertexDraws draws,
                      std::span<VertexNumbers> out) {
  assert(out.size() == paths.size());
  const size_t n = paths.size();
  if (n == 0) return;
  thread_local DrawLanes l;
  for (auto* v : {&l.hashedKey, &l.index, &l.bits, &l.x, &l.y}) v->resize(n);
  const SamplerKind kind = paths[0].kind;
  for (size_t i = 0; i < n; ++i) {
    assert(paths[i].kind == kind);
    const Sampler s = paths[i].bounce(depth);
    l.hashedKey[i] = s.hashedKey;
    l.index[i] = s.index;
    out[i] = VertexNumbers{};  // the draws not made stay 0, as in drawVertexNumbers
  }
  uint32_t dim = 0;
  if (draws.lights) {
    draw1D(l, kind, dim++, n);
    for (size_t i = 0; i < n; ++i) out[i].lightPick = toUnitFloat(l.x[i]);
    dim = draw2D(l, kind, dim, n);
    for (size_t i = 0; i < n; ++i) out[i].lightPoint = {toUnitFloat(l.x[i]), toUnitFloat(l.y[i])};
  }
  dim = draw2D(l, kind, dim, n);
  for (size_t i = 0; i < n; ++i) out[i].bsdf = {toUnitFloat(l.x[i]), toUnitFloat(l.y[i])};
  if (draws.roulette) {
    draw1D(l, kind, dim, n);
    for (size_t i = 0; i < n; ++i) out[i].roulette = toUnitFloat(l.x[i]);
  }
}

}  // namespace photovr
