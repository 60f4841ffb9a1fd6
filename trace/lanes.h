// Arithmetic written once for one value (float) and for eight (F8, GCC's vector extension),
// for the tracer's SIMD stages (trace/hit_geometry.cpp, trace/brdf_lanes.cpp): the same
// operations in the same order per lane, branch-free (selects instead of conditions), so
// a stage over a batch gives each lane the bits the scalar code gives that value. Only
// +, -, *, / and sqrt, all correctly rounded in both forms; nothing here may be compiled
// with FMA contraction (the stages' AVX2 clones do not enable FMA).
//
// Include only in translation units of trace/ (-fno-math-errno: sqrt stays inline).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

// -Wpsabi warns that 32-byte vectors pass differently with and without AVX; these helpers
// are always inlined, so no call crosses that boundary.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace photovr::lanes {

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
[[gnu::always_inline]] inline float minOf(float a, float b) {
  return std::min(a, b);
}
[[gnu::always_inline]] inline F8 minOf(const F8& a, const F8& b) {
  return b < a ? b : a;  // std::min's (b < a) ? b : a
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
// floor(v + 0.5) for v + 0.5 in [0, 2^31): truncation is floor there.
[[gnu::always_inline]] inline float roundedOf(float v) {
  return float(int32_t(v + 0.5f));
}
[[gnu::always_inline]] inline F8 roundedOf(const F8& v) {
  return __builtin_convertvector(__builtin_convertvector(v + 0.5f, I8), F8);
}
// std::clamp(v, lo, hi): v < lo ? lo : (hi < v ? hi : v); NaN stays NaN.
template <typename T>
[[gnu::always_inline]] inline T clampOf(const T& v, float lo, float hi) {
  const T l = T{} + lo, h = T{} + hi;
  return select(v < lo, l, select(h < v, h, v));
}
// trace/sampling.h's isFinite: v - v == 0 (false for NaN and +-Inf).
template <typename T>
[[gnu::always_inline]] inline auto finiteOf(const T& v) {
  return v - v == 0.0f;
}

template <typename T>
struct V3 {
  T x, y, z;
};

template <typename T>
[[gnu::always_inline]] inline V3<T> minus(const V3<T>& a, const V3<T>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <typename T>
[[gnu::always_inline]] inline V3<T> cross(const V3<T>& a, const V3<T>& b) {  // glm's order
  return {a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y};
}
template <typename T>
[[gnu::always_inline]] inline T dot(const V3<T>& a, const V3<T>& b) {  // glm's: (x + y) + z
  return (a.x * b.x + a.y * b.y) + a.z * b.z;
}
// glm::normalize: v * (1 / sqrt(dot(v, v))).
template <typename T>
[[gnu::always_inline]] inline V3<T> normalized(const V3<T>& v) {
  const T inv = 1.0f / sqrtOf(dot(v, v));
  return {v.x * inv, v.y * inv, v.z * inv};
}

// sin and cos of a in [-pi/4, pi/4] by their Taylor series to a^9 and a^10: the first
// omitted terms, a^11 / 11! and a^12 / 12!, are below 1.8e-9 there, under half an ulp of
// the results (>= 0.7 for cos). In Horner form, so every lane rounds alike; replaces
// libm's sinf/cosf in the sampling warps, whose vector forms (libmvec) do not give the
// scalar bits.
template <typename T>
[[gnu::always_inline]] inline void sinCosQuarter(const T& a, T& s, T& c) {
  const T a2 = a * a;
  s = a *
      (1.0f + a2 * (-1.0f / 6 + a2 * (1.0f / 120 + a2 * (-1.0f / 5040 + a2 * (1.0f / 362880)))));
  c = 1.0f + a2 * (-0.5f + a2 * (1.0f / 24 + a2 * (-1.0f / 720 +
                                                   a2 * (1.0f / 40320 + a2 * (-1.0f / 3628800)))));
}

// sin and cos of 2 pi u for u in [0, 1): u's quadrant q = round(4u) is taken out exactly
// (4u - q is exact for 4u in [0, 4)), the rest is a quarter turn's angle in [-pi/4, pi/4],
// and the quadrant rotates the result.
template <typename T>
[[gnu::always_inline]] inline void sinCos2Pi(const T& u, T& s, T& c) {
  const T y = 4.0f * u;
  const T q = roundedOf(y);
  T sa, ca;
  sinCosQuarter((y - q) * 1.57079632679489661923f, sa, ca);
  // q mod 4 (4 is 0): 0 -> (s, c), 1 -> (c, -s), 2 -> (-s, -c), 3 -> (-c, s).
  const auto odd = (q == 1.0f) | (q == 3.0f);
  const T s1 = select(odd, ca, sa), c1 = select(odd, sa, ca);
  s = select((q == 2.0f) | (q == 3.0f), -s1, s1);
  c = select((q == 1.0f) | (q == 2.0f), -c1, c1);
}

}  // namespace photovr::lanes

#pragma GCC diagnostic pop
