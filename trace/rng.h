// Counter-based random numbers: every number is a pure function of where it is used
// (pixel, eye, frame, sample, bounce, dimension), so a frame is bit-identical whatever the
// number of threads or the order in which tiles run, and no generator state is shared.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/sobol.h"

namespace photovr {

// PCG-RXS-M-XS 32-bit output permutation applied to one LCG step, as "pcg" in Jarzynski &
// Olano, "Hash Functions for GPU Rendering", JCGT 9(3), 2020, sec. 2 and listing 1; the
// paper finds it the best quality/speed trade-off of the 1D hashes it measures.
inline uint32_t pcgHash(uint32_t v) {
  const uint32_t state = v * 747796405u + 2891336453u;
  const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// Several inputs by nesting, hash(x + hash(y)) (Jarzynski & Olano 2020, sec. 2): a change
// in any input changes every output bit with probability ~1/2.
inline uint32_t hashCombine(uint32_t seed, uint32_t v) {
  return pcgHash(v + pcgHash(seed));
}

// The top 24 bits scaled by 2^-24: every value is exactly representable in float and the
// largest is 1 - 2^-24 < 1, so samplers may rely on u < 1 (a 32-bit integer * 2^-32 would
// round up to 1.0f).
inline float toUnitFloat(uint32_t bits) {
  return float(bits >> 8) * 0x1p-24f;
}

// Where one path vertex draws its numbers. `seed` is the user's --seed.
struct SampleCounters {
  uint32_t pixel = 0;  // index of the pixel within its eye's image
  uint32_t eye = 0;
  uint32_t frame = 0;
  uint32_t sample = 0;  // sample index within the pixel and frame
  uint32_t bounce = 0;
  uint32_t seed = 0;
  uint32_t samplesPerFrame = 1;  // n: the index spanning frames is frame * n + sample
  SamplerKind kind = SamplerKind::Random;
  uint32_t sampleIndex() const { return frame * samplesPerFrame + sample; }
};

// Numbers for one bounce: the `dim`-th draw of the stream keyed by the counters. Cheap to
// copy; a path makes a new one per bounce so that bounce k's numbers do not depend on how
// many bounce k-1 consumed.
//
// Random: draw d is hash(key, d), independent of every other number. Sobol: draw d is the
// sample index's point of a shuffled, Owen-scrambled Sobol sequence (core/sobol.h) whose
// seed is hash(key, d), the key naming (seed, pixel, eye, bounce) but not the frame or the
// sample: so over the frames and samples of one pixel each draw runs through one
// stratified sequence, and draws of different pixels, eyes, bounces or --seed are
// independent scrambles. A 2D draw (next2) is one Sobol pair (dimensions 0 and 1, a (0, 2)
// net for every 2^m samples), under Random two independent numbers.
struct Sampler {
  uint32_t key = 0;
  uint32_t dim = 0;
  // pcgHash(key), the inner hash of every hashCombine(key, dim) this sampler draws: hashed
  // once here instead of once per number (the hashing was ~12 % of continuePath's own time).
  uint32_t hashedKey = pcgHash(0);
  uint32_t index = 0;  // Sobol: the sample index spanning frames
  SamplerKind kind = SamplerKind::Random;

  static Sampler make(const SampleCounters& c);
  float next() {
    const uint32_t bits = pcgHash(dim++ + hashedKey);
    if (kind == SamplerKind::Random) return toUnitFloat(bits);
    return toUnitFloat(shuffledSobol1D(index, bits));
  }
  glm::vec2 next2() {
    if (kind == SamplerKind::Random) {
      const float a = next();
      return {a, next()};
    }
    const glm::uvec2 p = shuffledSobol2D(index, pcgHash(dim++ + hashedKey));
    return {toUnitFloat(p.x), toUnitFloat(p.y)};
  }
};

// What every bounce of one path shares, hashed once per path: make(c).bounce(b) ==
// Sampler::make(c with bounce b).
struct PathSampler {
  uint32_t key = 0;
  uint32_t index = 0;
  SamplerKind kind = SamplerKind::Random;

  static PathSampler make(const SampleCounters& c) {
    uint32_t h = hashCombine(c.seed, c.pixel);
    h = hashCombine(h, c.eye);
    if (c.kind == SamplerKind::Sobol) return {h, c.sampleIndex(), c.kind};
    h = hashCombine(h, c.frame);
    return {hashCombine(h, c.sample), 0, c.kind};
  }
  Sampler bounce(uint32_t b) const {
    const uint32_t k = hashCombine(key, b);
    return {k, 0, pcgHash(k), index, kind};
  }
};

inline Sampler Sampler::make(const SampleCounters& c) {
  return PathSampler::make(c).bounce(c.bounce);
}

}  // namespace photovr
