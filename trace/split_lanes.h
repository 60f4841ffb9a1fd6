// Stereo reuse's split (trace/stereo_reuse.h, ReuseSplit) answered for a batch of reused
// right samples in SIMD lanes, eight at a time (an AVX2 clone where the CPU has it), with
// the bits of the scalar answerSplit: at a vertex whose material has neither glass nor
// layers and whose split is not whole, whether the left's bounce direction is the reused
// term's, and the right sample's own direction and whether it lies outside that term. On
// spheres, where every surface is curved and no split is whole, those two tests and the own
// sample were a tenth of the reusing eye's tracer as scalar code (perf, the eye alone).
#pragma once

#include <span>

#include <glm/glm.hpp>

#include "trace/bsdf.h"
#include "trace/sampling.h"
#include "trace/stereo_reuse.h"

namespace photovr {

// One reused sample's split, for splitAnswers: the left's record, the right vertex (its
// prepared BRDF, shading frame and geometric normal, and its BSDF's pdf towards the left's
// direction, or whether it has none to reuse), and the right's bounce numbers.
struct SplitJob {
  const FirstBounce* left;
  const BsdfVertex* right;
  const Frame* frame;
  glm::vec3 geometricNormal;
  bool reusing;          // the left sampled a bounce (VertexShading::reusing)
  float pdfTowardsLeft;  // the right BSDF's pdf at the left's direction, if reusing
  glm::vec2 u;
  SplitAnswers* out;
};
void splitAnswers(std::span<const SplitJob> jobs);

}  // namespace photovr
