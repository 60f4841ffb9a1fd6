#include "trace/bsdf_lanes.h"

#include <algorithm>
#include <cassert>
#include <vector>

#include "trace/scratch.h"

// -Wpsabi warns that 32-byte vectors pass differently with and without AVX; the lane helpers
// are always inlined, so no call crosses that boundary.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace photovr {
namespace {

using lanes::BrdfSampleOf;
using lanes::BrdfVertexOf;
using lanes::F8;
using lanes::V3;

// The BrdfVertexOf fields, in order, as floats of a BsdfVertex.
constexpr size_t kVertexFloats = 16;

void vertexFloats(const BsdfVertex& v, float* to) {
  const float from[kVertexFloats] = {
      v.wo.x,        v.wo.y,        v.wo.z,        v.alpha,
      v.f0.x,        v.f0.y,        v.f0.z,        v.diffuse.x,
      v.diffuse.y,   v.diffuse.z,   v.f90,         v.fresnelWo.x,
      v.fresnelWo.y, v.fresnelWo.z, v.g1OverCosWo, v.specularProbability};
  std::copy(from, from + kVertexFloats, to);
}

template <typename T>
BrdfVertexOf<T> fromFloats(const T* f) {
  return {{f[0], f[1], f[2]},
          f[3],
          {f[4], f[5], f[6]},
          {f[7], f[8], f[9]},
          f[10],
          {f[11], f[12], f[13]},
          f[14],
          f[15]};
}

// Eight vertices' inputs and samples, as vectors.
struct alignas(32) BrdfLanes8 {  // 32: see hit_geometry.cpp's Lanes8
  F8 vertex[kVertexFloats];
  F8 ux, uy;
  BrdfSampleOf<F8> sample;
};
static_assert(sizeof(BrdfVertexOf<float>) == kVertexFloats * sizeof(float));
static_assert(sizeof(BrdfVertexOf<F8>) == kVertexFloats * sizeof(F8));

__attribute__((target_clones("avx2", "default"))) void sampleLanes(BrdfLanes8* groups,
                                                                   size_t count) {
  for (size_t g = 0; g < count; ++g) {
    BrdfLanes8& l = groups[g];
    l.sample = lanes::sampleBrdfOf(fromFloats(l.vertex), l.ux, l.uy);
  }
}

void setLane(V3<F8>& to, size_t k, const glm::vec3& v) {
  to.x[k] = v.x, to.y[k] = v.y, to.z[k] = v.z;
}
glm::vec3 laneOf(const V3<F8>& v, size_t k) {
  return {v.x[k], v.y[k], v.z[k]};
}

// Eight parameter sets, views and light directions, and what they prepare to.
struct alignas(32) PrepareLanes8 {
  lanes::BrdfParamsOf<F8> params;
  V3<F8> wo, wi, wi2;
  BrdfVertexOf<F8> vertex;
  V3<F8> tint;
  lanes::BrdfEvalOf<F8> eval, eval2;
};

// 'second': evaluate at wi2 too.
__attribute__((target_clones("avx2", "default"))) void prepareLanes(PrepareLanes8* groups,
                                                                    size_t count, bool second) {
  for (size_t g = 0; g < count; ++g) {
    PrepareLanes8& l = groups[g];
    l.vertex = lanes::prepareBrdfOf(l.params, l.wo, l.tint);
    l.eval = lanes::evalBrdfPartsOf(l.vertex, l.wi).value;
    if (second) l.eval2 = lanes::evalBrdfPartsOf(l.vertex, l.wi2).value;
  }
}

BsdfEval evalOf(const lanes::BrdfEvalOf<F8>& e, size_t k) {
  return {{laneOf(e.diffuse, k), laneOf(e.specular, k)}, e.pdf[k]};
}

// prepareBsdf's vertex for plain parameters from lane k: its BRDF terms, the tint, and the
// coat's view, which prepareLayers sets to wo with no coat; the rest is BsdfVertex's default.
void storeVertex(const PrepareLanes8& l, size_t k, BsdfVertex& v) {
  v = BsdfVertex{};
  v.wo = v.coatWo = laneOf(l.vertex.wo, k);
  v.alpha = l.vertex.alpha[k];
  v.f0 = laneOf(l.vertex.f0, k);
  v.diffuse = laneOf(l.vertex.diffuse, k);
  v.f90 = l.vertex.f90[k];
  v.fresnelWo = laneOf(l.vertex.fresnelWo, k);
  v.g1OverCosWo = l.vertex.g1OverCosWo[k];
  v.specularProbability = l.vertex.specularProbability[k];
  v.tint = laneOf(l.tint, k);
}

}  // namespace

void prepareBrdfs(std::span<const BrdfPrepareJob> jobs) {
  const size_t n = jobs.size(), count = (n + 7) / 8;
  if (n == 0) return;
  bool second = false;
  for (const BrdfPrepareJob& job : jobs) second |= job.eval2 != nullptr;
  thread_local std::vector<PrepareLanes8> groups;
  growTo(groups, count);
  for (size_t i = 0; i < count * 8; ++i) {
    const BrdfPrepareJob& job = jobs[std::min(i, n - 1)];  // as in sampleBrdfs
    assert(plainBsdf(*job.params));
    const BsdfParams& p = *job.params;
    PrepareLanes8& l = groups[i / 8];
    const size_t k = i % 8;
    setLane(l.params.baseColor, k, p.baseColor);
    l.params.metallic[k] = p.metallic;
    l.params.roughness[k] = p.roughness;
    setLane(l.params.dielectricF0, k, p.dielectricF0);
    l.params.dielectricF90[k] = p.dielectricF90;
    setLane(l.wo, k, job.wo);
    setLane(l.wi, k, job.wi);
    setLane(l.wi2, k, job.wi2);
  }
  prepareLanes(groups.data(), count, second);
  for (size_t i = 0; i < n; ++i) {
    const PrepareLanes8& l = groups[i / 8];
    const size_t k = i % 8;
    storeVertex(l, k, *jobs[i].vertex);
    *jobs[i].eval = evalOf(l.eval, k);
    if (jobs[i].eval2) *jobs[i].eval2 = evalOf(l.eval2, k);
  }
}

BsdfSample sampleBrdf(const BsdfVertex& v, glm::vec2 u) {
  assert(v.glass == 0.0f);
  const BrdfSampleOf<float> s = lanes::sampleBrdfOf(brdfVertexOf(v), u.x, u.y);
  BsdfSample out;
  out.wi = vec3Of(s.wi);
  out.f = vec3Of(s.f);
  out.fDiffuse = vec3Of(s.fDiffuse);
  out.pdf = s.pdf;
  out.weight = vec3Of(s.weight);
  out.specularLobe = s.specularLobe;
  return out;
}

BsdfEval evalBrdf(const BsdfVertex& v, const glm::vec3& wi) {
  const lanes::BrdfEvalOf<float> e = lanes::evalBrdfPartsOf(brdfVertexOf(v), v3Of(wi)).value;
  return {{vec3Of(e.diffuse), vec3Of(e.specular)}, e.pdf};
}

void sampleBrdfs(std::span<const BsdfVertex* const> vertices, std::span<const glm::vec2> u,
                 std::span<BsdfSample> out) {
  assert(u.size() == vertices.size() && out.size() == vertices.size());
  const size_t n = vertices.size(), count = (n + 7) / 8;
  if (n == 0) return;
  thread_local std::vector<BrdfLanes8> groups;
  growTo(groups, count);
  for (size_t i = 0; i < count * 8; ++i) {
    // Lanes past the end repeat the last vertex (their samples are dropped).
    const size_t from = std::min(i, n - 1), k = i % 8;
    BrdfLanes8& l = groups[i / 8];
    float f[kVertexFloats];
    vertexFloats(*vertices[from], f);
    for (size_t j = 0; j < kVertexFloats; ++j) l.vertex[j][k] = f[j];
    l.ux[k] = u[from].x;
    l.uy[k] = u[from].y;
  }
  sampleLanes(groups.data(), count);
  for (size_t i = 0; i < n; ++i) {
    const BrdfSampleOf<F8>& s = groups[i / 8].sample;
    const size_t k = i % 8;
    BsdfSample& o = out[i];
    o.wi = {s.wi.x[k], s.wi.y[k], s.wi.z[k]};
    o.f = {s.f.x[k], s.f.y[k], s.f.z[k]};
    o.fDiffuse = {s.fDiffuse.x[k], s.fDiffuse.y[k], s.fDiffuse.z[k]};
    o.pdf = s.pdf[k];
    o.weight = {s.weight.x[k], s.weight.y[k], s.weight.z[k]};
    o.specularLobe = s.specularLobe[k] != 0;
  }
}

}  // namespace photovr
