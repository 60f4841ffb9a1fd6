// The BSDF stage of the batched tracer (issue 20): a bounce's BSDFs prepared, evaluated
// towards NEE's light and sampled eight at a time in SIMD lanes (an AVX2 clone where the CPU
// has it, else SSE2), for the vertices whose material has neither glass nor layers; the
// same results, bit for bit, as the scalar functions of trace/bsdf.h. The lanes' code is
// trace/bsdf_lanes.h.
#pragma once

#include <span>

#include <glm/glm.hpp>

#include "trace/bsdf.h"

namespace photovr {

// Parameters that prepareBsdf gives neither glass nor layers, whatever the others are.
inline bool plainBsdf(const BsdfParams& p) {
  return p.transmission == 0.0f && p.clearcoat == 0.0f && p.sheenColor == glm::vec3(0.0f);
}

// A prepared vertex without glass or layers.
inline bool plainBrdf(const BsdfVertex& v) {
  return v.glass == 0.0f && !v.layered;
}

// The BSDF stage's first half: *vertex = prepareBsdf(*params, wo) and *eval =
// evalBsdfAndPdf(*vertex, wi) (NEE's light direction), and where eval2 is set *eval2 at wi2
// (a reused right sample's bounce direction), for parameters without glass or layers
// (plainBsdf), eight at a time, to the bit.
struct BrdfPrepareJob {
  const BsdfParams* params;
  glm::vec3 wo, wi;
  BsdfVertex* vertex;
  BsdfEval* eval;
  glm::vec3 wi2{0.0f};
  BsdfEval* eval2 = nullptr;
};
void prepareBrdfs(std::span<const BrdfPrepareJob> jobs);

// The BSDF stage's second half: out[i] = sampleBrdf(*vertices[i], u[i]), eight at a time (an AVX2
// clone where the CPU has it), to the bit.
void sampleBrdfs(std::span<const BsdfVertex* const> vertices, std::span<const glm::vec2> u,
                 std::span<BsdfSample> out);

// sampleBsdf(v, u) for a vertex without glass or layers (plainBrdf(v)), one at a time; with
// layers, their base's BRDF (v.glass 0).
BsdfSample sampleBrdf(const BsdfVertex& v, glm::vec2 u);

// evalBsdfAndPdf(v, wi) for a vertex without glass or layers, one at a time.
BsdfEval evalBrdf(const BsdfVertex& v, const glm::vec3& wi);

}  // namespace photovr
