// The metallic-roughness BRDF's preparation, evaluation and sampling, written once for one
// vertex (float: what prepareBsdf, evalBsdfAndPdf, sampleBsdf, sampleCosineHemisphere and
// sampleGgxVndf run) and for eight (F8: the batched tracer's BSDF stage, trace/
// bsdf_stage.h), in trace/lanes.h's form: the same operations in the
// same order, each expression in glm's order, so a vertex sampled in a batch gets the
// scalar bits. The formulas and their sources are trace/bsdf.h's.
//
// Include only in translation units of trace/.
#pragma once

#include <cfloat>
#include <cstdint>
#include <span>

#include "trace/bsdf.h"
#include "trace/bsdf_stage.h"
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

// What prepareBsdf reads of BsdfParams without glass or layers, and what it makes of them
// (the BrdfVertexOf below, and the clamped base colour, BsdfVertex::tint).
template <typename T>
struct BrdfParamsOf {
  V3<T> baseColor;
  T metallic, roughness;
  V3<T> dielectricF0;
  T dielectricF90;
};

// glm::clamp(v, 0, 1) = min(max(v, 0), 1), glm's max (a < b ? b : a) and min (b < a ? b : a).
template <typename T>
[[gnu::always_inline]] inline T unitOf(const T& v) {
  return minOf(maxOf(v, T{} + 0.0f), T{} + 1.0f);
}
// prepareBsdf's clamps: a vector with a component that is not finite is 0, a number that
// is not finite is 0, the rest clamped into [0, 1] (glm::clamp for vectors, std::clamp for
// numbers: the same for finite values).
template <typename T>
[[gnu::always_inline]] inline V3<T> unitColourOf(const V3<T>& c) {
  const auto finite = finiteOf(c.x) & finiteOf(c.y) & finiteOf(c.z);
  const T zero = T{} + 0.0f;
  return {unitOf(select(finite, c.x, zero)), unitOf(select(finite, c.y, zero)),
          unitOf(select(finite, c.z, zero))};
}
template <typename T>
[[gnu::always_inline]] inline T unitNumberOf(const T& v) {
  return select(finiteOf(v), clampOf(v, 0.0f, 1.0f), T{} + 0.0f);
}

// roughnessToAlpha: r = roughness > 0 ? min(roughness, 1) : 0 (NaN -> 0), max(r^2, kMinAlpha).
template <typename T>
[[gnu::always_inline]] inline T roughnessToAlphaOf(const T& roughness) {
  const T r = select(roughness > 0.0f, minOf(roughness, T{} + 1.0f), T{} + 0.0f);
  return maxOf(r * r, T{} + kMinAlpha);
}

// luminance(): Rec. 709 weights, in its order.
template <typename T>
[[gnu::always_inline]] inline T luminanceOf(const V3<T>& c) {
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
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

// prepareBsdf's BRDF terms from the clamped base colour, the BRDF's metallic (the glass
// lobe's re-weighted one where there is glass), the clamped dielectric f0 and f90, alpha and
// wo: glm::mix(df0, base, m) = df0 (1 - m) + base m; f90 = df90 + (1 - df90) m, exactly 1
// for df90 = 1; and specularProbability's lum(F) against lum((1 - F) diffuse).
template <typename T>
[[gnu::always_inline]] inline BrdfVertexOf<T> brdfTermsOf(const V3<T>& base, const T& metallic,
                                                          const V3<T>& df0, const T& df90,
                                                          const T& alpha, const V3<T>& wo) {
  BrdfVertexOf<T> v;
  v.wo = wo;
  v.alpha = alpha;
  const T keep = 1.0f - metallic;
  v.f0 = {df0.x * keep + base.x * metallic, df0.y * keep + base.y * metallic,
          df0.z * keep + base.z * metallic};
  v.f90 = df90 + (1.0f - df90) * metallic;
  v.diffuse = {keep * base.x, keep * base.y, keep * base.z};
  v.fresnelWo = fresnelSchlickOf(v.f0, v.f90, wo.z);
  v.g1OverCosWo = ggxG1OverCosOf(wo, alpha);
  const T spec = luminanceOf(v.fresnelWo);
  const T diff =
      luminanceOf(V3<T>{(1.0f - v.fresnelWo.x) * v.diffuse.x, (1.0f - v.fresnelWo.y) * v.diffuse.y,
                        (1.0f - v.fresnelWo.z) * v.diffuse.z});
  v.specularProbability = select(diff <= 0.0f, T{} + 1.0f, spec / (spec + diff));
  return v;
}

// prepareBsdf of parameters without glass or layers (plainBsdf).
template <typename T>
[[gnu::always_inline]] inline BrdfVertexOf<T> prepareBrdfOf(const BrdfParamsOf<T>& p,
                                                            const V3<T>& wo, V3<T>& tint) {
  tint = unitColourOf(p.baseColor);
  return brdfTermsOf(tint, unitNumberOf(p.metallic), unitColourOf(p.dielectricF0),
                     unitNumberOf(p.dielectricF90), roughnessToAlphaOf(p.roughness), wo);
}

// evalBsdfAndPdf of a BsdfVertex without glass or layers: the lobes' values and the pdf,
// zero unless wo and wi are both above the surface with a half-vector (reflectionPair).
template <typename T>
struct BrdfEvalOf {
  V3<T> diffuse, specular;
  T pdf;
};
template <typename T>
struct BrdfEvalParts {  // what a sample's f reuses: the half-vector's D and G terms
  BrdfEvalOf<T> value;
  Mask<T> pair;
};
template <typename T>
[[gnu::always_inline]] inline BrdfEvalParts<T> evalBrdfPartsOf(const BrdfVertexOf<T>& v,
                                                               const V3<T>& wi) {
  const T zero = T{} + 0.0f;
  V3<T> h = {v.wo.x + wi.x, v.wo.y + wi.y, v.wo.z + wi.z};
  const T len2 = dot(h, h);
  const T inv = 1.0f / sqrtOf(len2);
  h = {h.x * inv, h.y * inv, h.z * inv};
  const T d = ggxDOf(h, v.alpha);
  const T p = v.specularProbability;
  const T pdf = p * (v.g1OverCosWo * d * 0.25f) + (1.0f - p) * (maxOf(zero, wi.z) * kLaneInvPi);
  const V3<T> fWi = fresnelSchlickOf(v.f0, v.f90, wi.z);
  const auto lambert = [&](const T& fo, const T& fi, const T& albedo) {
    return (1.0f - fo) * (1.0f - fi) * albedo * kLaneInvPi;
  };
  const V3<T> fd = {lambert(v.fresnelWo.x, fWi.x, v.diffuse.x),
                    lambert(v.fresnelWo.y, fWi.y, v.diffuse.y),
                    lambert(v.fresnelWo.z, fWi.z, v.diffuse.z)};
  const V3<T> fh = fresnelSchlickOf(v.f0, v.f90, dot(v.wo, h));
  const T g = d * v.g1OverCosWo * ggxG1OverCosOf(wi, v.alpha) * 0.25f;
  const Mask<T> pair = (v.wo.z > 0.0f) & (wi.z > 0.0f) & (len2 > 0.0f);
  BrdfEvalParts<T> e;
  e.value.diffuse = {select(pair, fd.x, zero), select(pair, fd.y, zero), select(pair, fd.z, zero)};
  e.value.specular = {select(pair, fh.x * g, zero), select(pair, fh.y * g, zero),
                      select(pair, fh.z * g, zero)};
  e.value.pdf = select(pair, pdf, zero);
  e.pair = pair;
  return e;
}

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
  const BrdfEvalParts<T> e = evalBrdfPartsOf(v, wi);
  const T pdf = e.value.pdf;
  const auto ok = e.pair & (pdf > 0.0f) & finiteOf(pdf);
  const V3<T>& fd = e.value.diffuse;
  const V3<T> f = {e.value.specular.x + fd.x, e.value.specular.y + fd.y, e.value.specular.z + fd.z};
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

// A BsdfVertex's BRDF terms as the templates read them, and back.
inline lanes::V3<float> v3Of(const glm::vec3& v) {
  return {v.x, v.y, v.z};
}
inline glm::vec3 vec3Of(const lanes::V3<float>& v) {
  return {v.x, v.y, v.z};
}
inline lanes::BrdfVertexOf<float> brdfVertexOf(const BsdfVertex& v) {
  return {v3Of(v.wo), v.alpha,           v3Of(v.f0),    v3Of(v.diffuse),
          v.f90,      v3Of(v.fresnelWo), v.g1OverCosWo, v.specularProbability};
}
inline void setBrdfTerms(BsdfVertex& v, const lanes::BrdfVertexOf<float>& t) {
  v.wo = vec3Of(t.wo);
  v.alpha = t.alpha;
  v.f0 = vec3Of(t.f0);
  v.diffuse = vec3Of(t.diffuse);
  v.f90 = t.f90;
  v.fresnelWo = vec3Of(t.fresnelWo);
  v.g1OverCosWo = t.g1OverCosWo;
  v.specularProbability = t.specularProbability;
}

}  // namespace photovr
