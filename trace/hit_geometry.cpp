#include "trace/hit_geometry.h"

#include <algorithm>
#include <cassert>
#include <cfloat>
#include <cstring>
#include <vector>

#include "trace/lanes.h"
#include "trace/scratch.h"

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
using lanes::absOf;
using lanes::cross;
using lanes::dot;
using lanes::F8;
using lanes::I8;
using lanes::maxOf;
using lanes::minus;
using lanes::select;
using lanes::sqrtOf;
using lanes::V3;

template <typename T>
struct Corners {
  V3<T> m0, m1, m2, m3;  // the instance transform's columns (its w row is 0 0 0 1)
  V3<T> p0, p1, p2;      // the triangle's object-space vertices
  V3<T> n0, n1, n2;      // ... and their normals (zero where the mesh has none)
};
template <typename T>
struct Result {
  V3<T> position, ng;
  T error;
  V3<T> normal;  // the interpolated vertex normal in world space, unit (ng where none)
};

template <typename T>
[[gnu::always_inline]] inline V3<T> toWorld(const Corners<T>& c, const V3<T>& p) {
  return {(c.m0.x * p.x + c.m1.x * p.y) + (c.m2.x * p.z + c.m3.x * 1.0f),
          (c.m0.y * p.x + c.m1.y * p.y) + (c.m2.y * p.z + c.m3.y * 1.0f),
          (c.m0.z * p.x + c.m1.z * p.y) + (c.m2.z * p.z + c.m3.z * 1.0f)};
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

// v / |v|, or 'fallback' where |v| is 0 or not finite (surfaceAt's safeNormalize, which
// computed the interpolated normal before this stage: glm::length is sqrt(dot(v, v)), and
// v / len divides each component).
template <typename T>
[[gnu::always_inline]] inline V3<T> unitOr(const V3<T>& v, const V3<T>& fallback) {
  const T len = sqrtOf(dot(v, v));
  const auto ok = (len > 0.0f) & (len <= FLT_MAX);
  return {select(ok, v.x / len, fallback.x), select(ok, v.y / len, fallback.y),
          select(ok, v.z / len, fallback.z)};
}

// The vertex normals interpolated at (b1, b2) and taken to world space, unit; the unit
// geometric normal 'ng' where that vanishes (no normals, or normals cancelling out). As
// surfaceAt computed it with glm: b0 * n0 + b1 * n1 + b2 * n2 with b0 = 1 - b1 - b2, then
// the transform's cofactor matrix (the inverse transpose up to a positive scale: cross
// products of its columns, negated where its determinant is negative) times it.
template <typename T>
[[gnu::always_inline]] inline V3<T> interpolatedNormalOf(const Corners<T>& c, const T& b1,
                                                         const T& b2, const V3<T>& ng) {
  const T b0 = (1.0f - b1) - b2;
  const auto lerp = [&](const T& a0, const T& a1, const T& a2) {
    return (b0 * a0 + b1 * a1) + b2 * a2;
  };
  const V3<T> n = {lerp(c.n0.x, c.n1.x, c.n2.x), lerp(c.n0.y, c.n1.y, c.n2.y),
                   lerp(c.n0.z, c.n1.z, c.n2.z)};
  V3<T> c0 = cross(c.m1, c.m2), c1 = cross(c.m2, c.m0), c2 = cross(c.m0, c.m1);
  const auto flip = dot(c.m0, c0) < 0.0f;
  const auto signed_ = [&](V3<T>& v) {
    v = {select(flip, -v.x, v.x), select(flip, -v.y, v.y), select(flip, -v.z, v.z)};
  };
  signed_(c0), signed_(c1), signed_(c2);
  const auto row = [&](const T& x, const T& y, const T& z) {
    return (x * n.x + y * n.y) + z * n.z;
  };
  return unitOr(V3<T>{row(c0.x, c1.x, c2.x), row(c0.y, c1.y, c2.y), row(c0.z, c1.z, c2.z)}, ng);
}

template <typename T>
[[gnu::always_inline]] inline Result<T> geometryOf(const Corners<T>& c, const T& b1, const T& b2) {
  Result<T> r = geometryOf(toWorld(c, c.p0), toWorld(c, c.p1), toWorld(c, c.p2), b1, b2);
  r.normal = interpolatedNormalOf(c, b1, b2, r.ng);
  return r;
}

template <typename T>
struct NamedResult {
  Result<T> geometry;
  T b1, b2, t;
  decltype(T{} < T{}) outside;  // bool, or I8's all-ones lanes
};

// A ray that names its triangle: Moller-Trumbore (1997) without culling, as the G-buffer
// shader computes it (shaders/gbuffer.frag); where the ray is parallel to the triangle, the
// named barycentrics (the rasterizer's); barycentrics outside the triangle clamped into it
// and flagged. Clamping is written without conditions: max(b, 0) and the division by a sum
// above 1 change nothing inside the triangle, so applying them always gives the bits of
// applying them only outside (NaN stays NaN either way).
template <typename T>
[[gnu::always_inline]] inline NamedResult<T> namedHitOf(const Corners<T>& c, const V3<T>& origin,
                                                        const V3<T>& dir, const T& b1,
                                                        const T& b2) {
  const V3<T> p0 = toWorld(c, c.p0), p1 = toWorld(c, c.p1), p2 = toWorld(c, c.p2);
  const V3<T> e1 = minus(p1, p0), e2 = minus(p2, p0);
  const V3<T> pv = cross(dir, e2);
  const T det = dot(e1, pv);
  const T inv = 1.0f / det;
  const V3<T> tv = minus(origin, p0);
  const V3<T> qv = cross(tv, e1);
  const auto parallel = det == 0.0f;
  const T zero = T{} + 0.0f, one = T{} + 1.0f;
  T u = select(parallel, b1, dot(tv, pv) * inv), v = select(parallel, b2, dot(dir, qv) * inv);
  NamedResult<T> r;
  r.outside = parallel | (u < 0.0f) | (v < 0.0f) | (u + v > 1.0f);
  u = maxOf(u, zero);
  v = maxOf(v, zero);
  const T sum = u + v;
  const auto over = sum > one;
  r.b1 = select(over, u / sum, u);
  r.b2 = select(over, v / sum, v);
  r.geometry = geometryOf(p0, p1, p2, r.b1, r.b2);
  r.geometry.normal = interpolatedNormalOf(c, r.b1, r.b2, r.geometry.ng);
  r.t = dot(minus(r.geometry.position, origin), dir);
  return r;
}

V3<float> v3(const glm::vec3& v) {
  return {v.x, v.y, v.z};
}

// The gather reads each hit's triangle indices, then its corners: each a miss to L3 at
// every new triangle. They are asked for ahead, in two steps: the indices kIndexLookahead
// hits ahead, the corners (positions and normals, which the gather reads, and the first
// texture coordinates, which surfaceAt reads after the batch) half as far ahead, from the
// indices asked for before. The first read of a vertex normal in surfaceAt had been a sixth
// of its time (perf annotate, spheres). A mesh built in code may lack normals or texture
// coordinates.
constexpr size_t kIndexLookahead = 16, kCornerLookahead = 8;

const Mesh& meshOf(const Scene& scene, const HitRef& hit) {
  return scene.meshes[size_t(scene.instances[hit.instance].mesh)];
}

void prefetchIndices(const Scene& scene, const HitRef& hit) {
  __builtin_prefetch(&meshOf(scene, hit).indices[3 * size_t(hit.triangle)]);
}

void prefetchCorners(const Scene& scene, const HitRef& hit) {
  const Mesh& mesh = meshOf(scene, hit);
  const uint32_t* idx = &mesh.indices[3 * size_t(hit.triangle)];
  const bool normals = !mesh.normals.empty(), uvs = !mesh.uv0.empty();
  for (int k = 0; k < 3; ++k) {
    __builtin_prefetch(mesh.positions.data() + idx[k]);
    if (normals) __builtin_prefetch(mesh.normals.data() + idx[k]);
    if (uvs) __builtin_prefetch(mesh.uv0.data() + idx[k]);
  }
}

// Both prefetches for the hit 'i' of 'count' will gather in some hits' time.
template <typename HitAt>
void prefetchAhead(const Scene& scene, size_t i, size_t count, const HitAt& hitAt) {
  if (i + kIndexLookahead < count) prefetchIndices(scene, hitAt(i + kIndexLookahead));
  if (i + kCornerLookahead < count) prefetchCorners(scene, hitAt(i + kCornerLookahead));
}

V3<float> normalOrZero(const Mesh& mesh, uint32_t index) {
  return mesh.normals.empty() ? V3<float>{0.0f, 0.0f, 0.0f} : v3(mesh.normals[index]);
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
          v3(mesh.positions[idx[2]]),
          normalOrZero(mesh, idx[0]),
          normalOrZero(mesh, idx[1]),
          normalOrZero(mesh, idx[2])};
}

// The last hit's corners, gathered again only at a new triangle: a batch's hits come in pixel
// order, so neighbours often share one (2/3 of spheres' gathers, 37-39 % of atrium's and
// cornell's at 240x270, primary and bounce hits together), and each gather is a chain of
// dependent loads (instance, mesh, indices, then the corners).
class LastCorners {
 public:
  const Corners<float>& of(const Scene& scene, const HitRef& hit) {
    if (hit.instance != instance_ || hit.triangle != triangle_) {
      corners_ = cornersOf(scene, hit);
      instance_ = hit.instance, triangle_ = hit.triangle;
    }
    return corners_;
  }

 private:
  uint32_t instance_ = ~0u, triangle_ = ~0u;
  Corners<float> corners_;
};

glm::vec3 toGlm(const V3<float>& v) {
  return {v.x, v.y, v.z};
}

HitGeometry toHitGeometry(const Result<float>& r) {
  return {toGlm(r.position), r.error, toGlm(r.ng), toGlm(r.normal)};
}

// Lane k of eight hits' corners, barycentrics and results, as vectors.
struct alignas(32) Lanes8 {  // 32: F8 is only 16-aligned where AVX is off, but the AVX2 clone
                             // loads it with aligned 32-byte moves
  Corners<F8> corners;
  F8 b1, b2;
  Result<F8> result;
};
constexpr size_t kCornerFloats = 30;
static_assert(sizeof(Corners<float>) == kCornerFloats * sizeof(float));
static_assert(sizeof(Corners<F8>) == kCornerFloats * sizeof(F8));
static_assert(alignof(Lanes8) == 32);

__attribute__((target_clones("avx2", "default"))) void geometryLanes(Lanes8* lanes, size_t count) {
  for (size_t g = 0; g < count; ++g)
    lanes[g].result = geometryOf(lanes[g].corners, lanes[g].b1, lanes[g].b2);
}

struct alignas(32) NamedLanes8 {  // eight named rays, as Lanes8
  Corners<F8> corners;
  V3<F8> origin, dir;
  F8 b1, b2;
  NamedResult<F8> result;
};
static_assert(alignof(NamedLanes8) == 32);

__attribute__((target_clones("avx2", "default"))) void namedHitLanes(NamedLanes8* lanes,
                                                                     size_t count) {
  for (size_t g = 0; g < count; ++g) {
    NamedLanes8& l = lanes[g];
    l.result = namedHitOf(l.corners, l.origin, l.dir, l.b1, l.b2);
  }
}

glm::vec3 laneOf(const V3<F8>& v, size_t k) {
  return {v.x[k], v.y[k], v.z[k]};
}

HitGeometry toHitGeometry(const Result<F8>& r, size_t k) {
  return {laneOf(r.position, k), r.error[k], laneOf(r.ng, k), laneOf(r.normal, k)};
}

// Writes lane k of 'lanes' (kCornerFloats floats per lane, in Corners' order).
template <typename Lanes>
void setCorners(Lanes& lanes, size_t k, const Corners<float>& c) {
  const float* from = &c.m0.x;
  float* to = &lanes.corners.m0.x[0];
  for (size_t j = 0; j < kCornerFloats; ++j) to[8 * j + k] = from[j];
}

}  // namespace

HitGeometry hitGeometry(const Scene& scene, const HitRef& hit) {
  return toHitGeometry(geometryOf(cornersOf(scene, hit), hit.b1, hit.b2));
}

HitGeometry hitGeometry(const WorldTriangle& tri, float b1, float b2) {
  Result<float> r = geometryOf(v3(tri.p0), v3(tri.p1), v3(tri.p2), b1, b2);
  r.normal = r.ng;  // no vertex normals
  return toHitGeometry(r);
}

void hitGeometries(const Scene& scene, std::span<const HitRef> hits, std::span<HitGeometry> out) {
  assert(out.size() == hits.size());
  const size_t n = hits.size(), groups = (n + 7) / 8;
  thread_local std::vector<Lanes8> lanes;
  growTo(lanes, groups);
  LastCorners last;
  for (size_t i = 0; i < groups * 8; ++i) {
    // Lanes past the end repeat the last hit (their results are dropped).
    const HitRef& hit = hits[std::min(i, n - 1)];
    prefetchAhead(scene, i, n, [&](size_t j) -> const HitRef& { return hits[j]; });
    Lanes8& l = lanes[i / 8];
    setCorners(l, i % 8, last.of(scene, hit));
    l.b1[i % 8] = hit.b1;
    l.b2[i % 8] = hit.b2;
  }
  geometryLanes(lanes.data(), groups);
  for (size_t i = 0; i < n; ++i) out[i] = toHitGeometry(lanes[i / 8].result, i % 8);
}

NamedHit namedHit(const Scene& scene, const glm::vec3& origin, const NamedRay& ray) {
  const NamedResult<float> r =
      namedHitOf(cornersOf(scene, ray.hit), v3(origin), v3(ray.direction), ray.hit.b1, ray.hit.b2);
  return {
      {ray.hit.instance, ray.hit.triangle, r.b1, r.b2}, toHitGeometry(r.geometry), r.t, r.outside};
}

void namedHits(const Scene& scene, const glm::vec3& origin, std::span<const NamedRay> rays,
               std::span<NamedHit> out) {
  assert(out.size() == rays.size());
  const size_t n = rays.size(), groups = (n + 7) / 8;
  thread_local std::vector<NamedLanes8> lanes;
  growTo(lanes, groups);
  LastCorners last;
  for (size_t i = 0; i < groups * 8; ++i) {
    const NamedRay& ray = rays[std::min(i, n - 1)];  // as in hitGeometries
    prefetchAhead(scene, i, n, [&](size_t j) -> const HitRef& { return rays[j].hit; });
    NamedLanes8& l = lanes[i / 8];
    const size_t k = i % 8;
    setCorners(l, k, last.of(scene, ray.hit));
    l.origin.x[k] = origin.x, l.origin.y[k] = origin.y, l.origin.z[k] = origin.z;
    l.dir.x[k] = ray.direction.x, l.dir.y[k] = ray.direction.y, l.dir.z[k] = ray.direction.z;
    l.b1[k] = ray.hit.b1;
    l.b2[k] = ray.hit.b2;
  }
  namedHitLanes(lanes.data(), groups);
  for (size_t i = 0; i < n; ++i) {
    const NamedResult<F8>& r = lanes[i / 8].result;
    const size_t k = i % 8;
    out[i] = {{rays[i].hit.instance, rays[i].hit.triangle, r.b1[k], r.b2[k]},
              toHitGeometry(r.geometry, k),
              r.t[k],
              r.outside[k] != 0};
  }
}

}  // namespace photovr
