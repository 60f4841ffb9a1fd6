// The numbers one path vertex draws, drawn before it is shaded: in a batch they come from
// one vectorised pass over every path of the bounce (drawBatchNumbers), the first of the
// wavefront tracer's SIMD stages (issue 20), and they are the same bits Sampler gives one
// by one (trace/rng.h): the draws are integer hashing and Owen scrambling only, exact on
// any instruction set, so the scalar tracer and the batched one still agree bit for bit.
#pragma once

#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "trace/rng.h"

namespace photovr {

// In the order shadeVertex consumes them (Sampler's draws 0..3: light choice, light point,
// BSDF direction, Russian roulette). Without lights the light draws are not made, and the
// BSDF's and roulette's numbers are draws 0 and 1, as a Sampler that skipped them gives.
struct VertexNumbers {
  float lightPick = 0.0f;
  glm::vec2 lightPoint{0.0f};
  glm::vec2 bsdf{0.0f};
  float roulette = 0.0f;
};

// Which draws a bounce makes: the same for every path of a bounce (all are at one depth).
struct VertexDraws {
  bool lights = true;    // the scene has lights to sample (NEE)
  bool roulette = true;  // Russian roulette may end the path here
};

// One vertex's numbers, drawn by a Sampler as the scalar tracer does.
VertexNumbers drawVertexNumbers(const PathSampler& path, uint32_t depth, VertexDraws draws);

// drawVertexNumbers for every path: out[i] for paths[i], all of sampler kind 'kind' at
// 'depth'; out.size() == paths.size(). Runs 8 paths per instruction where the CPU has AVX2.
void drawBatchNumbers(std::span<const PathSampler> paths, uint32_t depth, VertexDraws draws,
                      std::span<VertexNumbers> out);

}  // namespace photovr
