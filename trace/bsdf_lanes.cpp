#include "trace/bsdf_lanes.h"

#include <algorithm>
#include <cassert>
#include <vector>

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

glm::vec3 vec3Of(const V3<float>& v) {
  return {v.x, v.y, v.z};
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

}  // namespace

BsdfSample sampleBrdf(const BsdfVertex& v, glm::vec2 u) {
  assert(v.glass == 0.0f);
  float f[kVertexFloats];
  vertexFloats(v, f);
  const BrdfSampleOf<float> s = lanes::sampleBrdfOf(fromFloats(f), u.x, u.y);
  BsdfSample out;
  out.wi = vec3Of(s.wi);
  out.f = vec3Of(s.f);
  out.fDiffuse = vec3Of(s.fDiffuse);
  out.pdf = s.pdf;
  out.weight = vec3Of(s.weight);
  out.specularLobe = s.specularLobe;
  return out;
}

void sampleBrdfs(std::span<const BsdfVertex* const> vertices, std::span<const glm::vec2> u,
                 std::span<BsdfSample> out) {
  assert(u.size() == vertices.size() && out.size() == vertices.size());
  const size_t n = vertices.size(), count = (n + 7) / 8;
  if (n == 0) return;
  thread_local std::vector<BrdfLanes8> groups;
  groups.resize(count);
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
