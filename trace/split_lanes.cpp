#include "trace/split_lanes.h"

#include <algorithm>
#include <vector>

#include "trace/bsdf_lanes.h"
#include "trace/scratch.h"

// -Wpsabi warns that 32-byte vectors pass differently with and without AVX; the lane helpers
// are always inlined, so no call crosses that boundary (a helper left out of line is called
// from the AVX2 clone with the default ABI: garbage in a build that does not inline it, as
// the sanitized one does not).
#pragma GCC diagnostic ignored "-Wpsabi"

namespace photovr {
namespace {

using lanes::BrdfVertexOf;
using lanes::dot;
using lanes::F8;
using lanes::I8;
using lanes::select;
using lanes::V3;
using Mask8 = I8;

// One sample's inputs, as the lanes read them (all floats; flags 0 or 1).
struct SplitIn {
  V3<F8> leftNormal, leftGeometricNormal, leftWo, leftDir;
  F8 leftWoAbove, leftSpecularProbability;
  V3<F8> rightWo;
  F8 alpha, g1OverCosWo, rightSpecularProbability;
  V3<F8> frameX, frameY, frameZ, rightGeometricNormal;
  F8 reusing, pdfTowardsLeft, ux, uy;
};

struct alignas(32) SplitLanes8 {  // 32: see hit_geometry.cpp's Lanes8
  SplitIn in;
  Mask8 leftDirReused, ownTraced;
};

// std::copysign(1.0f, v) lane by lane: 1 with v's sign bit.
[[gnu::always_inline]] inline F8 signOf(const F8& v) {
  return F8((I8(v) & int32_t(0x80000000u)) | I8(F8{} + 1.0f));
}

[[gnu::always_inline]] inline V3<F8> localOf(const V3<F8>& v, const V3<F8>& x, const V3<F8>& y,
                                             const V3<F8>& z) {
  return {dot(v, x), dot(v, y), dot(v, z)};  // Frame::toLocal
}

[[gnu::always_inline]] inline V3<F8> worldOf(const V3<F8>& v, const V3<F8>& x, const V3<F8>& y,
                                             const V3<F8>& z) {
  return {(v.x * x.x + v.y * y.x) + v.z * z.x, (v.x * x.y + v.y * y.y) + v.z * z.y,
          (v.x * x.z + v.y * y.z) + v.z * z.z};  // Frame::toWorld
}

// ReuseSplit's estimate of the left pdf at world direction w: its lobe in x1L's frame (x, y,
// n) for x1L's view, 0 where leftCovers says the left could not have drawn w.
struct LeftPdf {
  const SplitIn& in;
  V3<F8> x, y;
  BrdfVertexOf<F8> vertex;
  [[gnu::always_inline]] F8 operator()(const V3<F8>& w) const {
    const F8 zero = F8{} + 0.0f;
    const Mask8 covers = (in.leftWoAbove != 0.0f) & (dot(w, in.leftNormal) > 0.0f) &
                         (dot(w, in.leftGeometricNormal) > 0.0f);
    const F8 pdf = lanes::evalBrdfPartsOf(vertex, localOf(w, x, y, in.leftNormal)).value.pdf;
    return select(covers, pdf, zero);
  }
};

// orthonormalBasis (trace/sampling.h) of the left normal, and the left lobe
// (prepareBsdfPdf's: the right material's alpha, x1L's view and lobe choice).
[[gnu::always_inline]] inline LeftPdf leftPdfOf(const SplitIn& in) {
  const V3<F8>& n = in.leftNormal;
  const F8 sign = signOf(n.z);
  const F8 a = -1.0f / (sign + n.z);
  const F8 b = n.x * n.y * a;
  LeftPdf l{in,
            {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x},
            {b, sign + n.y * n.y * a, -n.y},
            {}};
  const F8 zero = F8{} + 0.0f;
  l.vertex.wo = localOf(in.leftWo, l.x, l.y, n);
  l.vertex.alpha = in.alpha;
  l.vertex.f0 = l.vertex.diffuse = l.vertex.fresnelWo = {zero, zero, zero};  // pdf reads none
  l.vertex.f90 = zero;
  l.vertex.g1OverCosWo = lanes::ggxG1OverCosOf(l.vertex.wo, in.alpha);
  l.vertex.specularProbability = in.leftSpecularProbability;
  return l;
}

__attribute__((target_clones("avx2", "default"))) void splitLanes(SplitLanes8* groups,
                                                                  size_t count) {
  for (size_t g = 0; g < count; ++g) {
    SplitLanes8& l = groups[g];
    const SplitIn& in = l.in;
    const LeftPdf leftPdf = leftPdfOf(in);
    l.leftDirReused = (in.reusing != 0.0f) & (dot(in.leftDir, in.rightGeometricNormal) > 0.0f) &
                      (in.pdfTowardsLeft <= kReusePdfRatio * leftPdf(in.leftDir));
    // The right's own sample (sampleBsdfDirection): only its direction and pdf are read.
    const F8 zero = F8{} + 0.0f;
    BrdfVertexOf<F8> right;
    right.wo = in.rightWo;
    right.alpha = in.alpha;
    right.f0 = right.diffuse = right.fresnelWo = {zero, zero, zero};
    right.f90 = zero;
    right.g1OverCosWo = in.g1OverCosWo;
    right.specularProbability = in.rightSpecularProbability;
    const lanes::BrdfSampleOf<F8> own = lanes::sampleBrdfOf(right, in.ux, in.uy);
    const V3<F8> wi = worldOf(own.wi, in.frameX, in.frameY, in.frameZ);
    const F8 side = dot(wi, in.rightGeometricNormal);  // sameSide (path_tracer.cpp)
    const Mask8 sameSide = (own.wi.z > 0.0f) ? (side > 0.0f) : ((side < 0.0f) & (own.wi.z < 0.0f));
    l.ownTraced = (own.pdf > 0.0f) & sameSide & ~(own.pdf <= kReusePdfRatio * leftPdf(wi));
  }
}

void setLane(V3<F8>& to, size_t k, const glm::vec3& v) {
  to.x[k] = v.x, to.y[k] = v.y, to.z[k] = v.z;
}

void setJob(SplitIn& in, size_t k, const SplitJob& job) {
  const FirstBounce& b = *job.left;
  setLane(in.leftNormal, k, b.normal);
  setLane(in.leftGeometricNormal, k, b.geometricNormal);
  setLane(in.leftWo, k, b.wo);
  setLane(in.leftDir, k, b.dir);
  in.leftWoAbove[k] = b.woAbove ? 1.0f : 0.0f;
  in.leftSpecularProbability[k] = b.specularProbability;
  const BsdfVertex& v = *job.right;
  setLane(in.rightWo, k, v.wo);
  in.alpha[k] = v.alpha;
  in.g1OverCosWo[k] = v.g1OverCosWo;
  in.rightSpecularProbability[k] = v.specularProbability;
  setLane(in.frameX, k, job.frame->x);
  setLane(in.frameY, k, job.frame->y);
  setLane(in.frameZ, k, job.frame->z);
  setLane(in.rightGeometricNormal, k, job.geometricNormal);
  in.reusing[k] = job.reusing ? 1.0f : 0.0f;
  in.pdfTowardsLeft[k] = job.pdfTowardsLeft;
  in.ux[k] = job.u.x;
  in.uy[k] = job.u.y;
}

}  // namespace

void splitAnswers(std::span<const SplitJob> jobs) {
  const size_t n = jobs.size(), groups = (n + 7) / 8;
  thread_local std::vector<SplitLanes8> lanes;
  growTo(lanes, groups);
  for (size_t i = 0; i < groups * 8; ++i)  // lanes past the end repeat the last job
    setJob(lanes[i / 8].in, i % 8, jobs[std::min(i, n - 1)]);
  splitLanes(lanes.data(), groups);
  for (size_t i = 0; i < n; ++i) {
    const SplitLanes8& l = lanes[i / 8];
    *jobs[i].out = {l.leftDirReused[i % 8] != 0, l.ownTraced[i % 8] != 0};
  }
}

}  // namespace photovr
