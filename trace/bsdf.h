// The material model of the thesis (Moschos 2019, sec. 2.1.2; ../shared/reference/
// thesis.md): a GGX microfacet specular lobe plus a Lambert diffuse lobe over the glTF
// metallic-roughness parameters, made robust for a path tracer.
//
// Every function works in the local shading frame, z = the shading normal, with unit
// directions pointing away from the surface (wo towards the viewer, wi towards the light).
// wo.z > 0 always (zero otherwise): the caller flips back-facing shading normals towards
// the viewer. Reflection has wi.z > 0; only the glass lobe (transmission > 0) gives
// wi.z < 0, through the surface. Nothing here returns NaN or Inf, for
// any input (tests/trace/bsdf_test.cpp, "Finite*").
#pragma once

#include <glm/glm.hpp>

#include "trace/sampling.h"  // isFinite, luminance

namespace photovr {

// Perceptual roughness is clamped below at 0.045, alpha = roughness^2 at 0.045^2 =
// 2.025e-3: Filament's floor for fp32 targets (MIN_PERCEPTUAL_ROUGHNESS in
// common_material.fs); the raster shaders should use the same so both paths agree on the
// sharpest highlight. Below it the GGX peak D(n) = 1/(pi alpha^2) passes 8e4 and the
// lobe (~alpha rad wide) nears the ~1e-7 rad error of a float direction reflected about a
// half-vector, so pdf(sample) drifts from the density the sampler followed and f cos / pdf
// of a sampled highlight stops being bounded.
//
// Roughness 0 is therefore a near-mirror GGX lobe of alpha = kMinAlpha, not a delta lobe:
// one code path, and every BSDF pdf stays finite, so MIS with light and environment
// sampling stays valid without special cases for "specular" bounces. The cost: reflected
// directions spread ~2 alpha rad (median ~0.25 degree, a few DK2 pixels) around the
// mirror direction, with GGX's long tail (0.2 % beyond 5 degrees).
inline constexpr float kMinPerceptualRoughness = 0.045f;
inline constexpr float kMinAlpha = kMinPerceptualRoughness * kMinPerceptualRoughness;

// Dielectric specular reflectance at normal incidence, glTF 2.0 Appendix B (IOR 1.5).
inline constexpr float kDielectricF0 = 0.04f;

struct BsdfParams {
  glm::vec3 baseColor{1.0f};  // linear, in [0,1]
  float metallic = 0.0f;      // in [0,1]
  float roughness = 1.0f;     // glTF perceptual roughness in [0,1]
  // The dielectric layer's Schlick Fresnel at normal and at grazing incidence, glTF's
  // dielectric_f0 = min(F0(ior) specularColor, 1) specular and dielectric_f90 = specular
  // (KHR_materials_ior, KHR_materials_specular); core glTF: 0.04 and 1.
  glm::vec3 dielectricF0{kDielectricF0};
  float dielectricF90 = 1.0f;
  // KHR_materials_transmission, in [0,1]: see "The glass lobe" below.
  float transmission = 0.0f;
  // The glass lobe's relative index: the far side's over the near (wo's) side's, ior when
  // entering a volume from outside, 1 / ior when leaving it; ior on a thin wall.
  float eta = 1.5f;
  bool thinWalled = true;  // no KHR_materials_volume: transmission does not bend
  // Layers over that base, glTF's order (see "The layers" below): KHR_materials_sheen's
  // colour (linear, [0,1]; black = no sheen) and perceptual roughness, then
  // KHR_materials_clearcoat's strength (in [0,1]; 0 = no coat) and perceptual roughness.
  glm::vec3 sheenColor{0.0f};
  float sheenRoughness = 0.0f;
  float clearcoat = 0.0f;
  float clearcoatRoughness = 0.0f;
  // The coat's own normal, unit, in the shading frame (z = the base's shading normal):
  // +z unless the coat's normal map (clearcoatNormalTexture) or the base's tilts one
  // against the other (glTF: without its own map the coat takes the interpolated normal,
  // not the base's normal-mapped one). The coat lobe and its Fresnel filter are evaluated
  // about it; the base and sheen about z.
  glm::vec3 coatNormal{0.0f, 0.0f, 1.0f};
};

// GGX alpha from glTF perceptual roughness (glTF 2.0 Appendix B: alpha = roughness^2),
// with the kMinAlpha floor above. Out-of-range and NaN roughness clamp into [0,1].
float roughnessToAlpha(float roughness);

// --- Microfacet terms (thesis sec. 2.1.2), all directions in the local frame. ----------

// GGX / Trowbridge-Reitz NDF, thesis D(h) = a^2 / (pi ((n.h)^2 (a^2 - 1) + 1)^2), written
// with h.x^2 + h.y^2 in place of 1 - (n.h)^2 (the same for unit h): near h = n the
// subtraction would cancel to zero in float exactly where a small-alpha lobe lives.
// Zero for h.z <= 0.
float ggxD(const glm::vec3& h, float alpha);

// Smith's Lambda for GGX (Heitz 2014, "Understanding the Masking-Shadowing Function in
// Microfacet-Based BRDFs", JCGT 3(2), eq. 72): (-1 + sqrt(1 + alpha^2 tan^2 theta)) / 2.
float ggxLambda(const glm::vec3& w, float alpha);

// The thesis's separable Smith G1(v) = 2 (n.v) / ((n.v) + sqrt(a^2 + (1 - a^2)(n.v)^2)),
// which equals 1 / (1 + Lambda). Zero for w.z <= 0.
float ggxG1(const glm::vec3& w, float alpha);

// G1(w) / (n.w) without the division: 2 / ((n.w) + sqrt(a^2 + (1 - a^2)(n.w)^2)). Bounded
// by 2/alpha as n.w -> 0, where G1 and n.w both vanish; the BRDF and pdfs use it so no
// grazing cosine is ever a divisor.
float ggxG1OverCos(const glm::vec3& w, float alpha);

// Schlick, "An Inexpensive BRDF Model for Physically-based Rendering", CGF 13(3), 1994,
// eq. 15: F = F0 + (1 - F0)(1 - cos)^5, cos clamped to [0,1].
glm::vec3 fresnelSchlick(const glm::vec3& f0, float cosTheta);
// With a reflectance f90 at grazing incidence in place of 1, as glTF's fresnel_mix:
// F = f0 + (f90 - f0)(1 - cos)^5. Bit-identical to the above for f90 = 1.
glm::vec3 fresnelSchlick(const glm::vec3& f0, float f90, float cosTheta);

// The exact Fresnel reflectance of unpolarised light at a smooth dielectric interface
// (pbrt-v4 eq. 9.5): cosThetaI on the incident side, eta = n_far / n_near. 1 under total
// internal reflection, 0 for eta = 1.
float fresnelDielectric(float cosThetaI, float eta);

// Heitz, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4), 2018, listing 1
// (isotropic): a microfacet normal h distributed as D_wo(h) below. Requires wo.z > 0.
glm::vec3 sampleGgxVndf(const glm::vec3& wo, float alpha, glm::vec2 u);

// The distribution of visible normals (Heitz 2018, eq. 1):
// D_wo(h) = G1(wo) max(0, wo.h) D(h) / wo.z, a density over h in solid angle.
float ggxVndfPdf(const glm::vec3& wo, const glm::vec3& h, float alpha);

// --- The sheen lobe (KHR_materials_sheen). ---------------------------------------------

// Sheen roughness is floored as the specular one is (kMinPerceptualRoughness): below it the
// Charlie peak at grazing half-vectors narrows under a few degrees.
float sheenRoughnessToAlpha(float sheenRoughness);

// The "Charlie" distribution (Estevez & Kulla 2017, eq. 2):
// D(h) = (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi), with sin^2 = h.x^2 + h.y^2.
float charlieD(const glm::vec3& h, float alpha);

// Their shadowing Lambda (sec. 3, the fitted curve with its 5 coefficients interpolated in
// (1 - alpha)^2; mirrored about cos 0.5 for cos > 0.5), as the glTF sheen extension gives.
float charlieLambda(float cosTheta, float alpha);

// The sheen BRDF with sheenColor 1 (f alone, without the cosine); zero unless both
// directions are above the surface.
float sheenBrdf(const glm::vec3& wo, const glm::vec3& wi, float alpha);

// E(cos, roughness) = the integral of sheenBrdf(wo, wi) n.wi over the hemisphere, the
// sheen's directional albedo, bilinear in a table integrated offline
// (trace/sheen_albedo_table.h, written by photovr_sheen_table).
float sheenAlbedo(float cosTheta, float sheenRoughness);

// --- The BSDF. -------------------------------------------------------------------------
//
// The glass lobe (KHR_materials_transmission): a share g = (1 - metallic) transmission of
// the BSDF is a rough dielectric interface (Walter, Marschner, Li, Torrance, "Microfacet
// Models for Refraction through Rough Surfaces", EGSR 2007) with the exact Fresnel
// reflectance F = fresnelDielectric(wo.h, eta) in place of Schlick's:
//   reflection   F D G / (4 |n.l||n.v|)                                        wi.z > 0
//   refraction   baseColor (1 - F) D G |wi.h||wo.h| / (|n.l||n.v| (wi.h + wo.h/eta)^2 eta^2)
//                (Walter eq. 21 in pbrt-v4's form, radiance transport: the 1/eta^2 makes
//                radiance entering and leaving a medium cancel)                  wi.z < 0
//   thin wall    baseColor (1 - F) D G / (4 |n.l||n.v|) at wi mirrored through the
//                surface: light passes unbent, spread by the roughness (glTF's thin-walled
//                transmission)                                                   wi.z < 0
// with G = G1(wo) G1(wi) on |cos|, and the rest of the BSDF, the metallic-roughness BRDF
// below with metallic' = metallic / (1 - g), weighted by 1 - g: so the metal keeps its
// share 'metallic' and the BTDF replaces the dielectric's diffuse lobe in proportion to
// transmission, as glTF's layering has it. The glass lobe ignores dielectricF0/F90: with
// Schlick, R + T at an interface would not sum to 1 where total internal reflection is, and
// a glass sphere in a white furnace would darken. g = 0 is the BRDF below to the bit.

// The layers (KHR_materials_sheen, KHR_materials_clearcoat): over the base B above,
//   f = coat + A_c (sheen + A_s B)
//   coat  = c F_c(wo.h) D(h) G / (4 |n.l||n.v|), GGX with the coat's own alpha, F_c Schlick
//           with f0 0.04 (KHR_materials_clearcoat: "the same as the specular term ... F0
//           equal 0.04"), reflection only
//   A_c   = (1 - c F_c(n.v)) (1 - c F_c(|n.l|)), the light the coat lets through on the
//           way in and on the way out
//   sheen = A_c sheenColor sheenBrdf(wo, wi) / max(1, E(n.v), E(n.l)), reflection only,
//           sheenBrdf = D_charlie(h) / ((1 + Lambda(n.v) + Lambda(n.l)) 4 |n.l||n.v|)
//           (Estevez & Kulla, "Production Friendly Microfacet Sheen BRDF", 2017, with
//           alpha = sheenRoughness^2 as the Khronos sample viewer)
//   A_s   = min(1 - max(sheenColor) E'(n.v), 1 - max(sheenColor) E'(|n.l|)), the sheen
//           extension's albedo scaling, E = sheenAlbedo() (the sheen's directional albedo),
//           E' = min(E, 1)
// The max(1, E(n.v), E(n.l)) is ours: Estevez & Kulla's fitted Lambda is too small at
// grazing angles for alpha < 0.07, where E reaches 1.19 at alpha 0.04 and 4.1 at the floor
// (photovr_sheen_table); dividing by it (symmetric, so reciprocal) keeps the sheen's albedo
// at most E' and the whole BSDF's at most 1, and changes nothing where E <= 1.
// The coat's A_c departs from the extension's 1 - c F_c(n.v) on purpose: that factor alone
// is not reciprocal, and light that crosses the coat twice is filtered twice (as the
// base's own diffuse lobe is, above). Without either layer this is the base to the bit.

// Evaluation convention: f alone, without the cosine; the caller multiplies by |wi.z|
// (as pbrt's BxDF::f). Reciprocal: evalBsdf(p, a, b) == evalBsdf(p, b, a).
//
// f = D F G / (4 (n.l)(n.v))                                    thesis specular lobe
//   + (1 - F(n.v)) (1 - F(n.l)) (1 - metallic) baseColor / pi   diffuse lobe
// with F0 = mix(0.04, baseColor, metallic), the specular F = Schlick at v.h (= l.h) and
// G = G1(l) G1(v). The diffuse lobe's "(1 - F)" is the light the interface transmits on
// the way in and on the way out, each by Schlick at the macro-surface angle: reciprocal
// by symmetry and, unlike (1 - F(v.h)) (glTF 2.0 Appendix B's fresnel_mix), it keeps
// the directional albedo <= 1 at grazing angles, where F(v.h) -> 1 only on the narrow
// mirror lobe while 1 - F(v.h) stays ~0.96 over the rest of the hemisphere (albedo up to
// ~1.7 for a smooth white dielectric at 89 degrees; tests/trace/bsdf_test.cpp,
// "EnergyDirectionalAlbedoAtMostOne").
glm::vec3 evalBsdf(const BsdfParams& p, const glm::vec3& wo, const glm::vec3& wi);

// The two lobes of evalBsdf separately (their sum is evalBsdf), for splitting radiance into
// diffuse and specular parts for the denoiser.
struct BsdfLobes {
  glm::vec3 diffuse{0.0f}, specular{0.0f};
  glm::vec3 total() const { return diffuse + specular; }
};
BsdfLobes evalBsdfLobes(const BsdfParams& p, const glm::vec3& wo, const glm::vec3& wi);

// Albedos that demodulate the two lobes' radiance (SVGF, Schied et al. 2017, sec. 4.1):
// diffuse = (1 - metallic) baseColor; specular = the split-sum directional albedo of the
// GGX lobe by Karis's analytic fit ("Physically Based Shading on Mobile", 2014), which
// needs no lookup table and is smooth in roughness and angle.
glm::vec3 diffuseAlbedo(const BsdfParams& p);
glm::vec3 specularAlbedo(const BsdfParams& p, float cosThetaO);

// Probability that sampleBsdf picks the specular lobe: its weight estimate lum(F(n.wo))
// against the diffuse lobe's lum((1 - F(n.wo))(1 - metallic) baseColor). For a white
// dielectric this is the thesis's "probability by the Fresnel term" (Algorithm 5), p =
// F(n.wo). With the lobe weights roughly the lobes' albedos, f cos / pdf of either lobe
// stays near the total albedo, so no clamp is needed; a lobe of zero weight (the diffuse
// lobe of a metal, the specular lobe of nothing) gets probability exactly 0.
float specularProbability(const BsdfParams& p, const glm::vec3& wo);

// The combined density of sampleBsdf over wi in solid angle, both lobes weighted by their
// selection probabilities (the pdf MIS needs).
float pdfBsdf(const BsdfParams& p, const glm::vec3& wo, const glm::vec3& wi);

struct BsdfSample {
  glm::vec3 wi{0.0f};
  glm::vec3 f{0.0f};         // evalBsdf(wo, wi)
  glm::vec3 fDiffuse{0.0f};  // evalBsdfLobes(wo, wi).diffuse, the diffuse lobe's part of f
  float pdf = 0.0f;          // pdfBsdf(wo, wi): the combined pdf, 0 = no sample
  glm::vec3 weight{0.0f};    // f * wi.z / pdf, the throughput factor
  bool specularLobe = false;
  bool valid() const { return pdf > 0.0f; }
};

// Picks a lobe with u.x against specularProbability(), stretches u.x back over [0, 1)
// within the lobe's share, then samples the lobe with u: GGX visible normals reflected
// about h, or the cosine-weighted hemisphere. Returns an invalid sample (pdf 0, weight 0)
// when wo.z <= 0 or the sampled wi is below the surface.
BsdfSample sampleBsdf(const BsdfParams& p, const glm::vec3& wo, glm::vec2 u);

// --- One path vertex. ------------------------------------------------------------------

// What the functions above derive from (p, wo) alone: the clamped parameters, F(n.wo),
// G1(wo) / n.wo and the lobe probability. A path vertex evaluates the BSDF and its pdf for
// the light sample, samples it, and (at the first vertex) splits the sample into lobes;
// with the per-call functions each of those re-derived these, and the half-vector and D(h)
// twice (BSDF evaluation was 10.7 % of an atrium bench_trace profile, 9.7 % after, relative
// to a constant Embree share). The functions above are the ones below on a fresh
// BsdfVertex, so both give bit-identical results.
struct BsdfVertex {
  glm::vec3 wo{0.0f, 0.0f, 1.0f};
  float alpha = kMinAlpha;
  glm::vec3 f0{kDielectricF0};
  glm::vec3 diffuse{0.0f};  // (1 - metallic) baseColor, the Lambert albedo before Fresnel
  float f90 = 1.0f;
  glm::vec3 fresnelWo{0.0f};         // fresnelSchlick(f0, f90, wo.z)
  float g1OverCosWo = 0.0f;          // ggxG1OverCos(wo, alpha)
  float specularProbability = 1.0f;  // within the BRDF
  // The glass lobe: its share g, its selection probability, and within it the probability
  // of reflecting (Fresnel at the macro-surface, clamped so both halves get samples).
  float glass = 0.0f;
  float brdfWeight = 1.0f;  // 1 - g
  float glassProbability = 0.0f;
  float reflectProbability = 1.0f;
  float eta = 1.5f;
  glm::vec3 tint{1.0f};  // baseColor, the transmitted light's filter
  bool thinWalled = true;
  // The layers ("The layers" above); none when both strengths are 0.
  bool layered = false;
  float coat = 0.0f;  // c
  float coatAlpha = kMinAlpha;
  float coatG1OverCosWo = 0.0f;
  float coatFresnelWo = 0.0f;  // c F_c(n_c.v)
  // A tilted coat (BsdfParams::coatNormal not +z): its normal, z of the coat's frame
  // (Frame::fromZ, built where needed), and wo in that frame.
  bool coatTilted = false;
  glm::vec3 coatNormal{0.0f, 0.0f, 1.0f};
  glm::vec3 coatWo{0.0f, 0.0f, 1.0f};
  glm::vec3 sheenColor{0.0f};
  float sheenRoughness = 0.0f;
  float sheenAlpha = 1.0f;
  float sheenMax = 0.0f;       // max(sheenColor)
  float sheenLambdaWo = 0.0f;  // charlieLambda(n.v)
  float sheenAlbedoWo = 0.0f;  // E(n.v)
  // Lobe choice: the coat, then the sheen, then the base (remaining probability).
  float coatProbability = 0.0f;
  float sheenProbability = 0.0f;
};
BsdfVertex prepareBsdf(const BsdfParams& p, const glm::vec3& wo);
// specularAlbedo(p, cosThetaO) from 'v', p's BsdfVertex prepared for any outgoing
// direction: without layers nothing it takes from v depends on that direction, so the
// tracer's vertex serves and the BSDF is not prepared a second time (~370 instructions a
// path); with layers it prepares its own.
glm::vec3 specularAlbedo(const BsdfVertex& v, const BsdfParams& p, float cosThetaO);

// evalBsdfLobes and pdfBsdf of one direction, sharing the half-vector and D(h).
struct BsdfEval {
  BsdfLobes f;
  float pdf = 0.0f;
};
BsdfEval evalBsdfAndPdf(const BsdfVertex& v, const glm::vec3& wi);
// evalBsdfAndPdf(v, wi).pdf, bit for bit, without the BSDF's value where there is only the
// metallic-roughness BRDF (no Fresnel, no G1(wi)): the stereo split's left pdf.
float pdfBsdf(const BsdfVertex& v, const glm::vec3& wi);
BsdfSample sampleBsdf(const BsdfVertex& v, glm::vec2 u);
// sampleBsdf(v, u)'s direction, lobe and pdf, bit for bit, and its validity; f, fDiffuse and
// the weight only where the BSDF has more than the metallic-roughness BRDF (else 0). For a
// sample that is kept only if its direction passes a test (the stereo split's own term):
// the kept one is sampled again, whole, from the same u.
BsdfSample sampleBsdfDirection(const BsdfVertex& v, glm::vec2 u);
// A vertex for pdfBsdf alone: pdfBsdf(prepareBsdfPdf(p, wo, s), wi) is, bit for bit, the pdf
// of prepareBsdf(p, wo) with its specularProbability set to s. Where p is the plain BRDF
// (no transmission, coat or sheen) it derives only what that pdf reads (alpha, G1(wo) /
// n.wo); its other fields, and so evalBsdfAndPdf and sampleBsdf of it, are not p's.
BsdfVertex prepareBsdfPdf(const BsdfParams& p, const glm::vec3& wo, float specularProbability);

}  // namespace photovr
