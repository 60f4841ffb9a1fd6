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
BsdfLobes directLight(const TraceContext& ctx, const PathVertex& v, const Frame& frame,
                      const BsdfVertex& bsdf, Sampler& sampler, uint64_t& rays) {
  if (ctx.lights.empty()) return {};
  const float uSelect = sampler.next();
  const LightSample ls = ctx.lights.sample(v.hit.position, uSelect, sampler.next2());
  if (!ls.valid() || glm::dot(ls.direction, v.hit.geometricNormal) <= 0.0f) return {};
  const glm::vec3 wiL = frame.toLocal(ls.direction);
  const BsdfEval e = evalBsdfAndPdf(bsdf, wiL);
  const BsdfLobes& f = e.f;
  if (f.total() == glm::vec3(0.0f)) return {};
  // The shadow ray runs from the offset origin to the light point itself (not along the
  // direction sampled from the unoffset hit): an offset of ~1e-4 m on a large triangle would
  // otherwise carry the ray into the light's plane before the shortened end.
  const glm::vec3 origin = offsetRayOrigin(v.hit, ls.direction);
  glm::vec3 shadowDir = ls.direction;
  float tfar = ls.distance;
  if (std::isfinite(ls.distance)) {
    const glm::vec3 toLight = v.hit.position + ls.direction * ls.distance - origin;
    tfar = glm::length(toLight);
    shadowDir = toLight / tfar;
    if (ls.isArea) tfar *= 1.0f - kShadowRayShorten;
  }
  ++rays;
  if (ctx.embree.occluded(origin, shadowDir, 0.0f, tfar)) return {};
  const float w = ls.isDelta ? 1.0f : powerHeuristic(1, ls.pdf, 1, e.pdf);
  const glm::vec3 scale = ls.radiance * (std::abs(wiL.z) * w / ls.pdf);
  return {f.diffuse * scale, f.specular * scale};
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

// Fraction of each channel of a BSDF-sampled direction's weight that belongs to the
// diffuse lobe: splitting by f_d / (f_d + f_s) keeps both parts unbiased (the expectation
// of f_d / f * f cos L / pdf is the integral of f_d cos L).
glm::vec3 diffuseShare(const BsdfSample& bs) {
  glm::vec3 share(0.0f);
  for (int k = 0; k < 3; ++k) share[k] = bs.f[k] > 0.0f ? bs.fDiffuse[k] / bs.f[k] : 0.0f;
  return share;
}

void addSplit(PathResult& r, const glm::vec3& contribution, const glm::vec3& share) {
  r.diffuse += contribution * share;
  r.specular += contribution * (1.0f - share);
}

}  // namespace

PathResult continuePath(const TraceContext& ctx, const SurfaceHit& start, const glm::vec3& wo,
                        SampleCounters counters) {
  PathResult result;
  PathVertex v{start, wo};
  glm::vec3 beta(1.0f), share(1.0f);  // share: diffuse fraction of the first bounce
  bool albedoSet = false;
  uint64_t rays = 0;
  const PathSampler path = PathSampler::make(counters);
  for (int depth = 0;; ++depth) {
    Sampler sampler = path.bounce(uint32_t(depth));
    if (!albedoSet && (v.hit.bsdf.roughness >= kMirrorRoughness || v.hit.bsdf.metallic < 1.0f)) {
      result.albedo = v.hit.bsdf.baseColor;
      albedoSet = true;
    }
    const Frame frame = Frame::fromZ(v.hit.shadingNormal);
    const BsdfVertex bsdf = prepareBsdf(v.hit.bsdf, frame.toLocal(v.wo));
    const BsdfLobes direct = directLight(ctx, v, frame, bsdf, sampler, rays);
    if (depth == 0) {
      result.diffuse += direct.diffuse;
      result.specular += direct.specular;
    } else {
      addSplit(result, beta * direct.total(), share);
    }
    const BsdfSample bs = sampleBsdf(bsdf, sampler.next2());
    if (!bs.valid()) break;
    const glm::vec3 wi = frame.toWorld(bs.wi);
    if (glm::dot(wi, v.hit.geometricNormal) <= 0.0f) break;  // shading normal leaked below
    if (depth == 0) share = diffuseShare(bs);
    beta *= bs.weight;
    // Whether the path ends at what this ray finds: the bounce cap, or Russian roulette
    // (thesis Algorithm 2: survive with the largest throughput channel, then rescale).
    // Decided before the ray is traced (the same number from this vertex's sampler as
    // after), so that a last hit is rebuilt only as far as its emission needs.
    bool last = depth >= ctx.settings.maxBounces;
    float survival = 1.0f;
    if (!last && depth + 1 >= ctx.settings.russianRouletteDepth) {
      survival = std::min(1.0f, std::max(beta.r, std::max(beta.g, beta.b)));
      last = !(sampler.next() < survival);
    }
    const TraceHit th = ctx.embree.intersect(offsetRayOrigin(v.hit, wi), wi, 0.0f, kInfinity);
    ++rays;
    SurfaceHit next;
    if (th.hit) {
      next = last ? surfaceEmissionAt(ctx.scene, th.instance, th.triangle, th.b1, th.b2, wi)
                  : surfaceAt(ctx.scene, th.instance, th.triangle, th.b1, th.b2, wi);
    }
    addSplit(result, beta * foundLight(ctx, v, th, th.hit ? &next : nullptr, wi, bs.pdf), share);
    if (!th.hit || last) break;
    beta /= survival;
    v = {next, -wi};
  }
  if (!albedoSet) result.albedo = v.hit.bsdf.baseColor;
  result.rays = uint32_t(rays);
  if (!finite(result.diffuse) || !finite(result.specular)) {
    result.diffuse = result.specular = glm::vec3(0.0f);
    result.rejected = 1;
  }
  result.radiance = result.diffuse + result.specular;
  return result;
}

}  // namespace photovr
