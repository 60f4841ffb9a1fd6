// The metallic-roughness BRDF's sampling, written once for one vertex (float: what
// sampleBsdf, sampleCosineHemisphere and sampleGgxVndf run) and for eight (F8: the batched
// tracer's BSDF stage, sampleBrdfs), in trace/lanes.h's form: the same operations in the
// same order, each expression in glm's order, so a vertex sampled in a batch gets the
// scalar bits. The formulas and their sources are trace/bsdf.h's.
//
// Include only in translation units of trace/.
#pragma once

#include <cfloat>
#include <cstdint>
#include <span>

#include "trace/bsdf.h"
#include "trace/lanes.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // as in trace/lanes.h

namespace photovr::lanes {

template <typename T>
using Mask = decltype(T{} < T{});  // bool, or I8's all-ones lanes

inline constexpr float kQuarterPi = 0.25f * 3.14159265358979323846f;
inline constexpr float kLanePi = 3.14159265358979323846f;
inline constexpr float kLaneInvPi = 0.31830988618379067154f;

// Shirley & Chiu's concentric map (trace/sampling.h): theta = (pi/4) o.y/o.x where |o.x| >
// |o.y|, else pi/2 - (pi/4) o.x/o.y, whose cosine and sine are the sine and cosine of the
// quarter angle.
template <typename T>
[[gnu::always_inline]] inline void concentricDiskOf(const T& ux, const T& uy, T& dx, T& dy) {
  const T ox = 2.0f * ux - 1.0f, oy = 2.0f * uy - 1.0f;
  const auto wide = absOf(ox) > absOf(oy);
  const T r = select(wide, ox, oy);
  T sa, ca;
  sinCosQuarter(kQuarterPi * select(wide, oy / ox, ox / oy), sa, ca);
  const auto centre = (ox == 0.0f) & (oy == 0.0f);
  const T zero = T{} + 0.0f;
  dx = select(centre, zero, r * select(wide, ca, sa));
  dy = select(centre, zero, r * select(wide, sa, ca));
}

// sampleCosineHemisphere: Malley's method over the concentric disk.
template <typename T>
[[gnu::always_inline]] inline V3<T> cosineHemisphereOf(const T& ux, const T& uy) {
  T dx, dy;
  concentricDiskOf(ux, uy, dx, dy);
  return {dx, dy, sqrtOf(maxOf(T{} + 0.0f, 1.0f - dx * dx - dy * dy))};
}

// sampleGgxVndf: Heitz 2018, listing 1 (trace/bsdf.cpp cites the sections).
template <typename T>
[[gnu::always_inline]] inline V3<T> ggxVndfOf(const V3<T>& wo, const T& alpha, const T& ux,
                                              const T& uy) {
  const T zero = T{} + 0.0f, one = T{} + 1.0f;
  const V3<T> vh = normalized(V3<T>{alpha * wo.x, alpha * wo.y, wo.z});
  const T lensq = vh.x * vh.x + vh.y * vh.y;
  const T len = sqrtOf(lensq);
  const auto tilted = lensq > 0.0f;
  const V3<T> t1 = {select(tilted, -vh.y / len, one), select(tilted, vh.x / len, zero), zero};
  const V3<T> t2 = cross(vh, t1);
  const T r = sqrtOf(ux);
  T sinPhi, cosPhi;
  sinCos2Pi(uy, sinPhi, cosPhi);
  const T p1 = r * cosPhi;
  const T s = 0.5f * (1.0f + vh.z);
  const T p2 = (1.0f - s) * sqrtOf(maxOf(zero, 1.0f - p1 * p1)) + s * (r * sinPhi);
  const T q = sqrtOf(maxOf(zero, 1.0f - p1 * p1 - p2 * p2));
  const V3<T> nh = {(p1 * t1.x + p2 * t2.x) + q * vh.x, (p1 * t1.y + p2 * t2.y) + q * vh.y,
                    (p1 * t1.z + p2 * t2.z) + q * vh.z};
  return normalized(V3<T>{alpha * nh.x, alpha * nh.y, maxOf(zero, nh.z)});
}

// ggxD, ggxG1OverCos, fresnelSchlick(f0, f90, cos) of trace/bsdf.h.
template <typename T>
[[gnu::always_inline]] inline T ggxDOf(const V3<T>& h, const T& alpha) {
  const T a2 = alpha * alpha;
  const T t = h.z * h.z + (h.x * h.x + h.y * h.y) / a2;
  return select(h.z > 0.0f, 1.0f / (kLanePi * a2 * t * t), T{} + 0.0f);
}
template <typename T>
[[gnu::always_inline]] inline T ggxG1OverCosOf(const V3<T>& w, const T& alpha) {
  const T root = sqrtOf(alpha * alpha * (w.x * w.x + w.y * w.y) + w.z * w.z);
  return select(w.z > 0.0f, 2.0f / (w.z + root), T{} + 0.0f);
}
template <typename T>
[[gnu::always_inline]] inline V3<T> fresnelSchlickOf(const V3<T>& f0, const T& f90,
                                                     const T& cosTheta) {
  const T m = 1.0f - clampOf(cosTheta, 0.0f, 1.0f);
  const T m2 = m * m;
  const T k = m2 * m2 * m;
  return {f0.x + (f90 - f0.x) * k, f0.y + (f90 - f0.y) * k, f0.z + (f90 - f0.z) * k};
}

// What sampling the BRDF reads of a BsdfVertex (no glass lobe, no layers).
template <typename T>
struct BrdfVertexOf {
  V3<T> wo;
  T alpha;
  V3<T> f0, diffuse;
  T f90;
  V3<T> fresnelWo;
  T g1OverCosWo, specularProbability;
};

template <typename T>
struct BrdfSampleOf {
  V3<T> wi, f, fDiffuse, weight;
  T pdf;
  Mask<T> specularLobe;
};

// The lobe's number u.x stretched back over [0, 1) (bsdf.cpp's remapLobeNumber).
template <typename T>
[[gnu::always_inline]] inline T remapLobeNumberOf(const T& ux, const T& p, const Mask<T>& first) {
  return minOf(select(first, ux / p, (ux - p) / (1.0f - p)), T{} + 0x1.fffffep-1f);
}

// sampleBsdf of a BsdfVertex without glass or layers: a lobe by u.x, its direction, and f,
// the diffuse lobe's part of it and the pdf recomputed from the direction; all zero where
// there is no sample. Both lobes' directions are computed and one is kept.
template <typename T>
[[gnu::always_inline]] inline BrdfSampleOf<T> sampleBrdfOf(const BrdfVertexOf<T>& v, const T& ux,
                                                           const T& uy) {
  const T zero = T{} + 0.0f;
  const T p = v.specularProbability;
  const Mask<T> specular = ux < p;
  const T u1 = remapLobeNumberOf(ux, p, specular);
  const V3<T> cosine = cosineHemisphereOf(u1, uy);
  const V3<T> m = ggxVndfOf(v.wo, v.alpha, u1, uy);
  const T twoOm = 2.0f * dot(v.wo, m);
  const V3<T> wi = {select(specular, twoOm * m.x - v.wo.x, cosine.x),
                    select(specular, twoOm * m.y - v.wo.y, cosine.y),
                    select(specular, twoOm * m.z - v.wo.z, cosine.z)};
  // The half-vector (reflectionPair), D(h) and the pdf (bsdf.cpp's pdf()).
  V3<T> h = {v.wo.x + wi.x, v.wo.y + wi.y, v.wo.z + wi.z};
  const T len2 = dot(h, h);
  const T inv = 1.0f / sqrtOf(len2);
  h = {h.x * inv, h.y * inv, h.z * inv};
  const T d = ggxDOf(h, v.alpha);
  const T pdf = p * (v.g1OverCosWo * d * 0.25f) + (1.0f - p) * (maxOf(zero, wi.z) * kLaneInvPi);
  const auto ok = (v.wo.z > 0.0f) & (wi.z > 0.0f) & (len2 > 0.0f) & (pdf > 0.0f) & finiteOf(pdf);
  // f's lobes (bsdf.cpp's diffuse() and specular()).
  const V3<T> fWi = fresnelSchlickOf(v.f0, v.f90, wi.z);
  const auto lambert = [&](const T& fo, const T& fi, const T& albedo) {
    return (1.0f - fo) * (1.0f - fi) * albedo * kLaneInvPi;
  };
  const V3<T> fd = {lambert(v.fresnelWo.x, fWi.x, v.diffuse.x),
                    lambert(v.fresnelWo.y, fWi.y, v.diffuse.y),
                    lambert(v.fresnelWo.z, fWi.z, v.diffuse.z)};
  const V3<T> fh = fresnelSchlickOf(v.f0, v.f90, dot(v.wo, h));
  const T g = d * v.g1OverCosWo * ggxG1OverCosOf(wi, v.alpha) * 0.25f;
  const V3<T> f = {fh.x * g + fd.x, fh.y * g + fd.y, fh.z * g + fd.z};
  const T scale = wi.z / pdf;
  BrdfSampleOf<T> s;
  s.wi = {select(ok, wi.x, zero), select(ok, wi.y, zero), select(ok, wi.z, zero)};
  s.f = {select(ok, f.x, zero), select(ok, f.y, zero), select(ok, f.z, zero)};
  s.fDiffuse = {select(ok, fd.x, zero), select(ok, fd.y, zero), select(ok, fd.z, zero)};
  s.weight = {select(ok, f.x * scale, zero), select(ok, f.y * scale, zero),
              select(ok, f.z * scale, zero)};
  s.pdf = select(ok, pdf, zero);
  s.specularLobe = ok & specular;
  return s;
}

}  // namespace photovr::lanes

#pragma GCC diagnostic pop

namespace photovr {

// sampleBsdf(v, u) for a vertex without glass or layers (plainBrdf(v)), one at a time; with
// layers, their base's BRDF (v.glass 0).
BsdfSample sampleBrdf(const BsdfVertex& v, glm::vec2 u);

inline bool plainBrdf(const BsdfVertex& v) {
  return v.glass == 0.0f && !v.layered;
}

// The BSDF stage: out[i] = sampleBrdf(*vertices[i], u[i]), eight at a time (an AVX2 clone
// where the CPU has it), to the bit.
void sampleBrdfs(std::span<const BsdfVertex* const> vertices, std::span<const glm::vec2> u,
                 std::span<BsdfSample> out);

}  // namespace photovr
