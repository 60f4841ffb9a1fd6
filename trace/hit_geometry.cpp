#include "trace/hit_geometry.h"

#include <algorithm>
#include <cassert>
#include <cfloat>
#include <cstring>
#include <vector>

// -Wpsabi warns that 32-byte vectors pass differently with and without AVX; these helpers
// are file-local and always inlined, so no call crosses that boundary.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace photovr {
namespace {

// Float error of the barycentric combination: a few ulp of the largest magnitude involved
// (pbrt-v4 sec. 6.8.5's bound for this form is gamma(7) * sum |terms|; 8 eps is a safe cap).
constexpr float kErrorUlps = 8.0f * 1.1920929e-7f;

// One hit's arithmetic, written once for a float (one hit) and for F8, eight hits in GCC's
// vector extension (the batch): the same operations in the same order per lane, each
// expression in glm's order (mat4 * vec4: (m0 x + m1 y) + (m2 z + m3 w); vec3 dot and
// length: (x + y) + z), so hitGeometry gives what surfaceAt computed with glm before and
// the batch gives hitGeometry's bits. Branch-free: selects instead of conditions.
using F8 = float __attribute__((vector_size(32)));
using I8 = int32_t __attribute__((vector_size(32)));

[[gnu::always_inline]] inline float absOf(float v) {
  return std::abs(v);
}
[[gnu::always_inline]] inline F8 absOf(const F8& v) {
  return F8(I8(v) & 0x7fffffff);
}
[[gnu::always_inline]] inline float maxOf(float a, float b) {
  return std::max(a, b);
}
[[gnu::always_inline]] inline F8 maxOf(const F8& a, const F8& b) {
  return a < b ? b : a;  // std::max's (a < b) ? b : a, lane by lane
}
[[gnu::always_inline]] inline float sqrtOf(float v) {
  return std::sqrt(v);
}
[[gnu::always_inline]] inline F8 sqrtOf(const F8& v) {
  F8 r;
  for (int k = 0; k < 8; ++k) r[k] = std::sqrt(v[k]);  // correctly rounded, as the scalar
  return r;
}
// ok ? a : b per lane.
[[gnu::always_inline]] inline float select(bool ok, float a, float b) {
  return ok ? a : b;
}
[[gnu::always_inline]] inline F8 select(const I8& ok, const F8& a, const F8& b) {
  return ok ? a : b;
}

template <typename T>
struct V3 {
  T x, y, z;
};
template <typename T>
struct Corners {
  V3<T> m0, m1, m2, m3;  // the instance transform's columns (its w row is 0 0 0 1)
  V3<T> p0, p1, p2;      // the triangle's object-space vertices
};
template <typename T>
struct Result {
  V3<T> position, ng;
  T error;
};

template <typename T>
[[gnu::always_inline]] inline V3<T> toWorld(const Corners<T>& c, const V3<T>& p) {
  return {(c.m0.x * p.x + c.m1.x * p.y) + (c.m2.x * p.z + c.m3.x * 1.0f),
          (c.m0.y * p.x + c.m1.y * p.y) + (c.m2.y * p.z + c.m3.y * 1.0f),
          (c.m0.z * p.x + c.m1.z * p.y) + (c.m2.z * p.z + c.m3.z * 1.0f)};
}

template <typename T>
[[gnu::always_inline]] inline V3<T> minus(const V3<T>& a, const V3<T>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}

// From the world-space corners.
template <typename T>
[[gnu::always_inline]] inline Result<T> geometryOf(const V3<T>& p0, const V3<T>& p1,
                                                   const V3<T>& p2, const T& b1, const T& b2) {
  const V3<T> e1 = minus(p1, p0), e2 = minus(p2, p0);
  // (p0 + b1 e1) + b2 e2, and the magnitudes of its terms, per component.
  const auto combine = [&](const T& a, const T& d1, const T& d2) {
    return (a + b1 * d1) + b2 * d2;
  };
  const auto magnitude = [&](const T& a, const T& d1, const T& d2) {
    return (absOf(a) + absOf(b1 * d1)) + absOf(b2 * d2);
  };
  Result<T> r;
  r.position = {combine(p0.x, e1.x, e2.x), combine(p0.y, e1.y, e2.y), combine(p0.z, e1.z, e2.z)};
  const T mx = magnitude(p0.x, e1.x, e2.x), my = magnitude(p0.y, e1.y, e2.y),
          mz = magnitude(p0.z, e1.z, e2.z);
  r.error = kErrorUlps * maxOf(mx, maxOf(my, mz));
  const V3<T> n = {e1.y * e2.z - e2.y * e1.z, e1.z * e2.x - e2.z * e1.x, e1.x * e2.y - e2.x * e1.y};
  const T len = sqrtOf((n.x * n.x + n.y * n.y) + n.z * n.z);
  const auto ok = (len > 0.0f) & (len <= FLT_MAX);  // neither degenerate nor overflowing
  const T zero = T{} + 0.0f, one = T{} + 1.0f;
  r.ng = {select(ok, n.x / len, zero), select(ok, n.y / len, one), select(ok, n.z / len, zero)};
  return r;
}

template <typename T>
[[gnu::always_inline]] inline Result<T> geometryOf(const Corners<T>& c, const T& b1, const T& b2) {
  return geometryOf(toWorld(c, c.p0), toWorld(c, c.p1), toWorld(c, c.p2), b1, b2);
}

V3<float> v3(const glm::vec3& v) {
  return {v.x, v.y, v.z};
}

Corners<float> cornersOf(const Scene& scene, const HitRef& hit) {
  const Instance& inst = scene.instances[hit.instance];
  const Mesh& mesh = scene.meshes[size_t(inst.mesh)];
  const uint32_t* idx = &mesh.indices[3 * size_t(hit.triangle)];
  const glm::mat4& m = inst.transform;
  return {v3(m[0]),
          v3(m[1]),
          v3(m[2]),
          v3(m[3]),
          v3(mesh.positions[idx[0]]),
          v3(mesh.positions[idx[1]]),
          v3(mesh.positions[idx[2]])};
}

HitGeometry toHitGeometry(const Result<float>& r) {
  return {{r.position.x, r.position.y, r.position.z}, r.error, {r.ng.x, r.ng.y, r.ng.z}};
}

// Lane k of eight hits' corners, barycentrics and results, as vectors.
struct alignas(32) Lanes8 {  // 32: F8 is only 16-aligned where AVX is off, but the AVX2 clone
                             // loads it with aligned 32-byte moves
  Corners<F8> corners;
  F8 b1, b2;
  Result<F8> result;
};
static_assert(sizeof(Corners<float>) == 21 * sizeof(float));
static_assert(sizeof(Corners<F8>) == 21 * sizeof(F8));
static_assert(alignof(Lanes8) == 32);

__attribute__((target_clones("avx2", "default"))) void geometryLanes(Lanes8* lanes, size_t count) {
  for (size_t g = 0; g < count; ++g)
    lanes[g].result = geometryOf(lanes[g].corners, lanes[g].b1, lanes[g].b2);
}

}  // namespace

HitGeometry hitGeometry(const Scene& scene, const HitRef& hit) {
  return toHitGeometry(geometryOf(cornersOf(scene, hit), hit.b1, hit.b2));
}

HitGeometry hitGeometry(const WorldTriangle& tri, float b1, float b2) {
  return toHitGeometry(geometryOf(v3(tri.p0), v3(tri.p1), v3(tri.p2), b1, b2));
}

void hitGeometries(const Scene& scene, std::span<const HitRef> hits, std::span<HitGeometry> out) {
  assert(out.size() == hits.size());
  const size_t n = hits.size(), groups = (n + 7) / 8;
  thread_local std::vector<Lanes8> lanes;
  lanes.resize(groups);
  for (size_t i = 0; i < groups * 8; ++i) {
    // Lanes past the end repeat the last hit (their results are dropped).
    const HitRef& hit = hits[std::min(i, n - 1)];
    const Corners<float> c = cornersOf(scene, hit);
    const float* from = &c.m0.x;
    float* to = &lanes[i / 8].corners.m0.x[0];
    for (size_t k = 0; k < 21; ++k) to[8 * k + i % 8] = from[k];
    lanes[i / 8].b1[i % 8] = hit.b1;
    lanes[i / 8].b2[i % 8] = hit.b2;
  }
  geometryLanes(lanes.data(), groups);
  for (size_t i = 0; i < n; ++i) {
    const Result<F8>& r = lanes[i / 8].result;
    const size_t k = i % 8;
    out[i] = {{r.position.x[k], r.position.y[k], r.position.z[k]},
              r.error[k],
              {r.ng.x[k], r.ng.y[k], r.ng.z[k]}};
  }
}

}  // namespace photovr
