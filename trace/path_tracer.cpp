#include "trace/path_tracer.h"

#include <cmath>
#include <limits>

#include "trace/bsdf.h"
#include "trace/sampling.h"

namespace photovr {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
// Shadow rays to area lights stop this fraction short of the sampled light point, so the
// light's own triangle never occludes it; 1e-4 of the distance is far above float rounding
// of the hit (~1e-7 relative) and far below any geometric feature between them.
constexpr float kShadowRayShorten = 1e-4f;
// Perceptual roughness below which a vertex counts as mirror-like for the albedo AOV (the
// denoiser wants the albedo of what the mirror shows; thesis §3.3.3).
constexpr float kMirrorRoughness = 0.1f;

struct PathVertex {
  SurfaceHit hit;
  glm::vec3 wo;
};

// Next-event estimation at one vertex, MIS-weighted against BSDF sampling for lights with
// area (Veach 1997 §9.2, power heuristic).
glm::vec3 directLight(const TraceContext& ctx, const PathVertex& v, const Frame& frame,
                      Sampler& sampler, uint64_t& rays) {
  if (ctx.lights.empty()) return glm::vec3(0.0f);
  const float uSelect = sampler.next();
  const LightSample ls = ctx.lights.sample(v.hit.position, uSelect, sampler.next2());
  if (!ls.valid() || glm::dot(ls.direction, v.hit.geometricNormal) <= 0.0f) return glm::vec3(0.0f);
  const glm::vec3 woL = frame.toLocal(v.wo), wiL = frame.toLocal(ls.direction);
  const glm::vec3 f = evalBsdf(v.hit.bsdf, woL, wiL) * std::abs(wiL.z);
  if (f == glm::vec3(0.0f)) return glm::vec3(0.0f);
  // The shadow ray starts at the offset origin, so its length is measured from there: the
  // offset (up to ~1e-4 m on large triangles) may exceed the shortening.
  const glm::vec3 origin = offsetRayOrigin(v.hit, ls.direction);
  float tfar = ls.distance;
  if (std::isfinite(ls.distance)) {
    tfar = glm::dot(v.hit.position + ls.direction * ls.distance - origin, ls.direction);
    if (ls.isArea) tfar *= 1.0f - kShadowRayShorten;
  }
  ++rays;
  if (ctx.embree.occluded(origin, ls.direction, 0.0f, tfar)) return glm::vec3(0.0f);
  const float w = ls.isDelta ? 1.0f : powerHeuristic(1, ls.pdf, 1, pdfBsdf(v.hit.bsdf, woL, wiL));
  return f * ls.radiance * (w / ls.pdf);
}

// Emission or environment found by a BSDF-sampled ray, MIS-weighted against NEE.
glm::vec3 foundLight(const TraceContext& ctx, const PathVertex& from, const TraceHit& th,
                     const SurfaceHit* to, const glm::vec3& wi, float bsdfPdf) {
  if (!th.hit) {
    const glm::vec3 le = ctx.lights.environmentRadiance(wi);
    if (le == glm::vec3(0.0f)) return le;
    return le * powerHeuristic(1, bsdfPdf, 1, ctx.lights.pdfEnvironment(wi));
  }
  if (to->emission == glm::vec3(0.0f)) return glm::vec3(0.0f);
  const float lightPdf = ctx.lights.pdfArea(th.instance, th.triangle, from.hit.position,
                                            to->position, to->geometricNormal);
  return to->emission * powerHeuristic(1, bsdfPdf, 1, lightPdf);
}

bool finite(const glm::vec3& v) {
  return isFinite(v);
}

}  // namespace

PathResult continuePath(const TraceContext& ctx, const SurfaceHit& start, const glm::vec3& wo,
                        SampleCounters counters) {
  PathResult result;
  PathVertex v{start, wo};
  glm::vec3 beta(1.0f);
  bool albedoSet = false;
  uint64_t rays = 0;
  for (int depth = 0;; ++depth) {
    counters.bounce = uint32_t(depth);
    Sampler sampler = Sampler::make(counters);
    if (!albedoSet && (v.hit.bsdf.roughness >= kMirrorRoughness || v.hit.bsdf.metallic < 1.0f)) {
      result.albedo = v.hit.bsdf.baseColor;
      albedoSet = true;
    }
    const Frame frame = Frame::fromZ(v.hit.shadingNormal);
    result.radiance += beta * directLight(ctx, v, frame, sampler, rays);
    const BsdfSample bs =
        sampleBsdf(v.hit.bsdf, frame.toLocal(v.wo), sampler.next2(), sampler.next());
    if (!bs.valid()) break;
    const glm::vec3 wi = frame.toWorld(bs.wi);
    if (glm::dot(wi, v.hit.geometricNormal) <= 0.0f) break;  // shading normal leaked below
    beta *= bs.weight;
    const TraceHit th = ctx.embree.intersect(offsetRayOrigin(v.hit, wi), wi, 0.0f, kInfinity);
    ++rays;
    SurfaceHit next;
    if (th.hit) next = surfaceAt(ctx.scene, th.instance, th.triangle, th.b1, th.b2, wi);
    result.radiance += beta * foundLight(ctx, v, th, th.hit ? &next : nullptr, wi, bs.pdf);
    if (!th.hit || depth >= ctx.settings.maxBounces) break;
    if (depth + 1 >= ctx.settings.russianRouletteDepth) {
      // Thesis Algorithm 2: survive with the largest throughput channel, then rescale.
      const float p = std::min(1.0f, std::max(beta.r, std::max(beta.g, beta.b)));
      if (!(sampler.next() < p)) break;
      beta /= p;
    }
    v = {next, -wi};
  }
  if (!albedoSet) result.albedo = v.hit.bsdf.baseColor;
  result.rays = uint32_t(rays);
  if (!finite(result.radiance)) {
    result.radiance = glm::vec3(0.0f);
    result.rejected = 1;
  }
  return result;
}

}  // namespace photovr
