// Counter-based random numbers: every number is a pure function of where it is used
// (pixel, eye, frame, sample, bounce, dimension), so a frame is bit-identical whatever the
// number of threads or the order in which tiles run, and no generator state is shared.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

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
};

// Numbers for one bounce: dimension `dim` of the stream keyed by the counters. Cheap to
// copy; a path makes a new one per bounce so that bounce k's numbers do not depend on how
// many bounce k-1 consumed.
struct Sampler {
  uint32_t key = 0;
  uint32_t dim = 0;
  // pcgHash(key), the inner hash of every hashCombine(key, dim) this sampler draws: hashed
  // once here instead of once per number (the hashing was ~12 % of continuePath's own time).
  uint32_t hashedKey = pcgHash(0);

  // The counters every bounce of one path shares, hashed once per path (pathKey) and
  // finished per bounce (forBounce): make(c) == forBounce(pathKey(c), c.bounce).
  static uint32_t pathKey(const SampleCounters& c) {
    uint32_t h = hashCombine(c.seed, c.pixel);
    h = hashCombine(h, c.eye);
    h = hashCombine(h, c.frame);
    return hashCombine(h, c.sample);
  }
  static Sampler forBounce(uint32_t pathKey, uint32_t bounce) {
    const uint32_t key = hashCombine(pathKey, bounce);
    return {key, 0, pcgHash(key)};
  }
  static Sampler make(const SampleCounters& c) { return forBounce(pathKey(c), c.bounce); }
  float next() { return toUnitFloat(pcgHash(dim++ + hashedKey)); }
  glm::vec2 next2() {
    const float a = next();
    return {a, next()};
  }
};

}  // namespace photovr
