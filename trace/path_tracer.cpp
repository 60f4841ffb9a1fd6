#include "trace/path_tracer.h"

#include <cmath>
#include <limits>
#include <new>
#include <type_traits>

#include "trace/bsdf.h"
#include "trace/caustics.h"
#include "trace/path_stages.h"
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

// Whether world direction 'wi' (wiLocal in the shading frame) leaves on the side of the
// geometry that the shading frame says: above it for reflection, below for transmission. A
// shading normal bent away from the geometric one (normal maps, interpolated normals) can
// otherwise send a reflected ray into the surface, or light through an opaque one.
bool sameSide(const glm::vec3& wi, const SurfaceHit& hit, const glm::vec3& wiLocal) {
  const float side = glm::dot(wi, hit.geometricNormal);
  return wiLocal.z > 0.0f ? side > 0.0f : side < 0.0f && wiLocal.z < 0.0f;
}

// A mirror or smooth glass: the albedo AOV takes what it shows (thesis sec. 3.3.3).
bool showsWhatIsBeyond(const BsdfParams& b) {
  return b.roughness < kMirrorRoughness && (b.metallic >= 1.0f || b.transmission > 0.0f);
}

// ... and one the denoiser looks through as well: no diffuse lobe and no sheen, so all it
// adds itself is specular (PathState::share).
bool seesThrough(const BsdfParams& b) {
  return showsWhatIsBeyond(b) && diffuseAlbedo(b) == glm::vec3(0.0f) &&
         b.sheenColor == glm::vec3(0.0f);
}

// The medium a ray leaving the path's vertex along 'dir' travels through: through a
// volume's surface, into the volume (front face) or out to what holds it (back face).
uint32_t mediumAlong(const Scene& scene, const PathState& p, const glm::vec3& dir) {
  const bool crosses = glm::dot(dir, p.hit.geometricNormal) < 0.0f;
  if (!crosses || !volumeMaterial(scene, p.hit.instance)) return p.media.current();
  return p.hit.frontFace ? p.hit.instance : p.media.outsideOf(p.hit.instance);
}

// Beer-Lambert over 'distance' in 'medium' (1 in air or a clear medium; 0 over an infinite
// distance in an absorbing one).
glm::vec3 transmittance(const Scene& scene, uint32_t medium, float distance) {
  const glm::vec3 sigma = mediumAbsorption(scene, medium);
  if (sigma == glm::vec3(0.0f)) return glm::vec3(1.0f);
  return std::isfinite(distance) ? glm::exp(-sigma * distance) : glm::vec3(0.0f);
}

// The shadow ray from the hit's offset origin to the light point itself (not along the
// direction sampled from the unoffset hit): an offset of ~1e-4 m on a large triangle would
// otherwise carry the ray into the light's plane before the shortened end. Embree takes an
// unnormalised direction (RTCRay(3): "The ray direction does not have to be normalized"), so
// the ray is the offset segment itself, t in [0, 1], with no square root or division; no
// reader of a shadow ray needs its length (its answer is blocked or not).
void setShadowRay(BatchRay& ray, const SurfaceHit& hit, const LightSample& ls) {
  const glm::vec3 origin = offsetRayOrigin(hit, ls.direction);
  if (!std::isfinite(ls.distance)) {
    ray.set(origin, ls.direction, 0.0f, ls.distance);
    return;
  }
  const glm::vec3 toLight = hit.position + ls.direction * ls.distance - origin;
  ray.set(origin, toLight, 0.0f, ls.isArea ? 1.0f - kShadowRayShorten : 1.0f);
}

// A reused right sample aims its NEE at the left sample's light point (the same numbers);
// where the left traced that shadow ray, its answer stands for the right's
// (trace/stereo_reuse.h, "The approximations"), but where it traces its own
// (tracesOwnShadowRay).
bool leftShadowAnswers(const PathState& p) {
  return p.reuse && p.reuse->shadowTraced && !p.ownShadowRay;
}

// Next-event estimation's light: its direction in the shading frame and whether it leaves
// on the side that frame says (vs.lit). vs.light is drawLight's.
void placeLight(const PathState& p, const Frame& frame, VertexShading& vs) {
  vs.lit = false;
  const LightSample& ls = vs.light;
  if (!ls.valid()) return;
  vs.wiL = frame.toLocal(ls.direction);
  vs.lit = sameSide(ls.direction, p.hit, vs.wiL);
}

// Whether NEE's light sample at the path's vertex closes a path that the light tracer of
// caustics takes (trace/caustics.h): a directional light (delta, at infinity) seen from a
// causticCaster whose vertices before it, 1 .. kCausticReceivers of them, are all
// causticReceivers. Then NEE leaves out the caster's specular lobe, which is the light
// tracer's.
bool lightTracedCaustic(const TraceContext& ctx, const PathState& p, const LightSample& ls) {
  return ctx.settings.caustics && p.depth >= 1 && int(p.depth) <= kCausticReceivers &&
         p.receiversBefore && ls.isDelta && ls.atInfinity() && causticCaster(p.hit.bsdf);
}

// Next-event estimation at the path's vertex, MIS-weighted against BSDF sampling for
// lights with area (Veach 1997 sec. 9.2, power heuristic), from the light sample and the
// BSDF's value and pdf towards it (vs.nee): what it adds unblocked and the shadow ray that
// decides it (none where the left's answers: leftShadowAnswers), weighted by the throughput
// and lobe split as they are at this vertex: by the lobes themselves at the denoiser
// surface ('splitsHere'), by the path's share elsewhere.
bool directLight(const TraceContext& ctx, const PathState& p, const VertexShading& vs,
                 ShadowRay& shadow) {
  const LightSample& ls = vs.light;
  BsdfLobes f = vs.nee.f;
  if (lightTracedCaustic(ctx, p, ls)) f.specular = glm::vec3(0.0f);
  if (f.total() == glm::vec3(0.0f)) return false;
  if (!leftShadowAnswers(p)) setShadowRay(shadow.ray, p.hit, ls);
  const float w = ls.isDelta ? 1.0f : powerHeuristic(1, ls.pdf, 1, vs.nee.pdf);
  glm::vec3 scale = ls.radiance * (std::abs(vs.wiL.z) * w / ls.pdf);
  // A light inside the medium the vertex is in is seen through that medium.
  const uint32_t medium = mediumAlong(ctx.scene, p, ls.direction);
  if (medium != MediumStack::kNone) scale *= transmittance(ctx.scene, medium, ls.distance);
  if (vs.splitsHere) {
    shadow.diffuse = p.beta * (f.diffuse * scale);  // beta is 1 at the start
    shadow.specular = p.beta * (f.specular * scale);
  } else {
    const glm::vec3 c = p.beta * (f.diffuse * scale + f.specular * scale);
    shadow.diffuse = c * p.share;
    shadow.specular = c * (1.0f - p.share);
  }
  return true;
}

// Emission or environment found by a BSDF-sampled ray, unweighted, and the density with
// which NEE samples it (for the MIS weight).
struct FoundLight {
  glm::vec3 emitted{0.0f};
  float lightPdf = 0.0f;
  // Whether 'emitted' is not zero. Kept rather than compared again in weighted: that
  // compare read the emission back from the stack in an 8-byte load across two stores,
  // which stalled on store forwarding (two fifths of advancePath's own time on cornell,
  // perf annotate).
  bool lit = false;
  // MIS-weighted against NEE for a ray sampled with density 'bsdfPdf'.
  glm::vec3 weighted(float bsdfPdf) const {
    if (!lit) return glm::vec3(0.0f);
    return emitted * powerHeuristic(1, bsdfPdf, 1, lightPdf);
  }
};

FoundLight foundLight(const TraceContext& ctx, const glm::vec3& from, const TraceHit& th,
                      const SurfaceHit* to, const glm::vec3& wi) {
  if (!th.hit) {
    const glm::vec3 le = ctx.lights.environmentRadiance(wi);
    if (le == glm::vec3(0.0f)) return {};
    return {le, ctx.lights.pdfEnvironment(wi), true};
  }
  if (to->emission == glm::vec3(0.0f)) return {};
  return {to->emission,
          ctx.lights.pdfArea(th.instance, th.triangle, from, to->position, to->geometricNormal),
          true};
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

// The right eye's bounce term from the left path's first bounce (trace/stereo_reuse.h
// derives it): no ray; the left's direction and the radiance it brought, re-weighted by
// this vertex's BSDF, and the emission it found MIS-weighted against this vertex's NEE;
// only if the direction is the reused term's ('split'), else the right sample's own.
void reuseBounce(const TraceContext& ctx, const PathState& p, const VertexShading& vs,
                 const SplitAnswers& split, PathResult& result) {
  const FirstBounce& b = *p.reuse;
  if (!split.leftDirReused) return;
  const glm::vec3& wiL = vs.wiReused;
  const BsdfEval& e = vs.reused;
  glm::vec3 incoming = b.beyond;
  if (b.emitted != glm::vec3(0.0f)) {
    const float lightPdf =
        b.hit ? ctx.lights.pdfArea(b.instance2, b.triangle2, p.hit.position, b.x2, b.n2)
              : b.environmentPdf;  // the same direction's: the environment is at infinity
    incoming += b.emitted * powerHeuristic(1, e.pdf, 1, lightPdf);
  }
  const glm::vec3 scale = incoming * (std::abs(wiL.z) / b.pdf);
  result.diffuse += e.f.diffuse * scale;
  result.specular += e.f.specular * scale;
}

}  // namespace

SplitAnswers answerWholeSplit(const PathState& p, const VertexShading& vs) {
  SplitAnswers a;
  // Only where the left path's bounce term was not 0 (a valid sample, not rejected), and its
  // direction leaves this vertex's side.
  a.leftDirReused = vs.reusing && glm::dot(p.reuse->dir, p.hit.geometricNormal) > 0.0f;
  return a;
}

SplitAnswers answerSplit(const PathState& p, const VertexShading& vs, const VertexNumbers& u) {
  const FirstBounce& b = *p.reuse;
  const ReuseSplit split(b, p.hit, vs.bsdf, p.wo);
  SplitAnswers a = answerWholeSplit(p, vs);
  if (split.whole()) return a;
  a.leftDirReused = a.leftDirReused && split.reused(b.dir, vs.reused.pdf);
  // A reused right sample traces its own bounce only where the reused term does not hold
  // the direction (trace/stereo_reuse.h): most do not, so its direction comes first, and the
  // BSDF's value only for a direction it keeps.
  const BsdfSample bs = sampleBsdfDirection(vs.bsdf, u.bsdf);
  if (!bs.valid()) return a;
  const glm::vec3 wi = vs.frame.toWorld(bs.wi);
  a.ownTraced = sameSide(wi, p.hit, bs.wi) && !split.reused(wi, bs.pdf);
  return a;
}

namespace {

glm::vec3 divideOrZero(const glm::vec3& a, const glm::vec3& b) {
  glm::vec3 q(0.0f);
  for (int k = 0; k < 3; ++k) q[k] = b[k] != 0.0f ? a[k] / b[k] : 0.0f;
  return q;
}

// The left path's second vertex as the right eye's reuse needs it.
void recordSecondVertex(PathState& p, const PathResult& result, const TraceHit& th,
                        const SurfaceHit& next, const FoundLight& found) {
  FirstBounce& b = *p.record;
  b.hit = th.hit;
  b.emitted = found.emitted;
  if (th.hit) {
    b.x2 = next.position;
    b.n2 = next.geometricNormal;
    b.instance2 = th.instance;
    b.triangle2 = th.triangle;
  } else {
    b.environmentPdf = found.lightPdf;
  }
  p.before0 = result.diffuse + result.specular;
}

// Beer-Lambert along the bounce segment (KHR_materials_volume), in the medium the path
// is in. A path with no medium that reaches a volume's back face started inside it (a
// camera in the glass): that volume's medium, as before nested media were tracked.
void absorbAlong(const Scene& scene, const PathState& p, const TraceHit& th, const SurfaceHit& next,
                 glm::vec3& beta) {
  uint32_t medium = p.media.current();
  if (medium == MediumStack::kNone && !next.frontFace) medium = th.instance;
  if (medium == MediumStack::kNone) return;
  const glm::vec3 sigma = mediumAbsorption(scene, medium);
  if (sigma != glm::vec3(0.0f)) beta *= glm::exp(-sigma * th.t);
}

}  // namespace

PathState startPath(const SurfaceHit& hit, const glm::vec3& wo, const SampleCounters& counters,
                    FirstBounce* record, const FirstBounce* reuse) {
  PathState p;
  startPath(p, hit, wo, counters, record, reuse);
  return p;
}

void startPath(PathState& p, const SurfaceHit& hit, const glm::vec3& wo,
               const SampleCounters& counters, FirstBounce* record, const FirstBounce* reuse) {
  p.hit = hit;
  p.wo = wo;
  p.receiversBefore = true;  // none before the first vertex
  p.sampler = reuse ? reuse->sampler : PathSampler::make(counters);
  p.record = record;
  p.reuse = reuse;
  if (record) {
    *record = FirstBounce{};
    record->position = hit.position;
    record->normal = hit.shadingNormal;
    record->geometricNormal = hit.geometricNormal;
    record->wo = wo;
    record->instance = hit.instance;
    record->sampler = p.sampler;
  }
}

void startReusedSample(PathState& p, const SurfaceHit& hit, const glm::vec3& wo,
                       const FirstBounce& reuse, bool ownShadowRay) {
  p.ownShadowRay = ownShadowRay;
  p.hit = hit;
  p.wo = wo;
  p.reuse = &reuse;
}

VertexDraws vertexDraws(const TraceContext& ctx, uint32_t depth) {
  return {!ctx.lights.empty(), int(depth) < ctx.settings.maxBounces &&
                                   int(depth) + 1 >= ctx.settings.russianRouletteDepth};
}

void drawLight(const TraceContext& ctx, const PathState& p, const VertexNumbers& u,
               VertexShading& vs) {
  LightSample& ls = vs.light;
  if (ctx.lights.empty()) {
    ls = LightSample{};
    return;
  }
  // A reused right sample draws the left's numbers: a light at infinity gives the left's
  // sample again, so it is taken from the record (stereo_reuse.h); a punctual one is
  // recorded for leftShadowEdge and sampled again from here.
  if (p.reuse && p.reuse->light.valid() && p.reuse->light.atInfinity())
    ls = p.reuse->light;
  else
    ctx.lights.sample(p.hit.position, u.lightPick, u.lightPoint, ls);
  if (p.record && p.depth == 0 && (ls.atInfinity() || ls.isDelta)) p.record->light = ls;
}

void startVertex(PathState& p, PathResult& result, VertexShading& vs) {
  if (!p.albedoSet && !showsWhatIsBeyond(p.hit.bsdf)) {
    result.albedo = p.hit.bsdf.baseColor;
    p.albedoSet = true;
  }
  vs.splitsHere = !p.split && !seesThrough(p.hit.bsdf);
  if (vs.splitsHere) {
    p.split = true;
    result.diffuseAlbedo = p.beta * diffuseAlbedo(p.hit.bsdf);
    if (p.depth > 0) result.guide = p.hit.shadingNormal * float(p.hit.instance + 1);
  }
  // The frame is built and used in registers, then stored: read back from vs.frame, its
  // 8-byte loads of what orthonormalBasis had stored in 4 and 8 bytes stalled on store
  // forwarding (13 % of startVertex's time, perf annotate).
  Frame frame;
  frame.setZ(p.hit.shadingNormal);
  vs.frame = frame;
  vs.wo = frame.toLocal(p.wo);
  placeLight(p, frame, vs);
  vs.reusing = p.reuse && p.reuse->sampled;
  vs.splitAnswered = false;
  if (vs.reusing) vs.wiReused = frame.toLocal(p.reuse->dir);
}

void prepareVertex(const BsdfParams& params, VertexShading& vs) {
  vs.bsdf = prepareBsdf(params, vs.wo);
  if (vs.lit) vs.nee = evalBsdfAndPdf(vs.bsdf, vs.wiL);
  if (vs.reusing) vs.reused = evalBsdfAndPdf(vs.bsdf, vs.wiReused);
}

void shadeSpecularAlbedo(const PathState& p, const VertexShading& vs, PathResult& result) {
  if (p.depth == 0)
    result.specularAlbedo =
        specularAlbedo(vs.bsdf, p.hit.bsdf, glm::dot(p.hit.shadingNormal, p.wo));
}

bool shadeVertexHead(const TraceContext& ctx, PathState& p, const VertexNumbers& u,
                     PathResult& result, ShadowRay& shadow, VertexShading& vs) {
  const BsdfVertex& bsdf = vs.bsdf;
  vs.rays = {};
  if (vs.lit && directLight(ctx, p, vs, shadow)) {
    if (leftShadowAnswers(p))
      resolveShadow(p, result, shadow, p.reuse->shadowBlocked);
    else
      vs.rays.shadow = true;
  }
  result.rays += vs.rays.shadow;
  if (p.depth == 0 && p.record) {
    p.record->numbers = u;
    p.record->woAbove = bsdf.wo.z > 0.0f;
    p.record->specularProbability = bsdf.specularProbability;
  }
  if (!p.reuse) return true;
  const SplitAnswers split = vs.splitAnswered ? vs.split : answerSplit(p, vs, u);
  reuseBounce(ctx, p, vs, split, result);
  if (!split.ownTraced) return false;
  ++result.ownBounces;
  p.reuse = nullptr;
  return true;
}

VertexRays shadeVertexTail(const TraceContext& ctx, PathState& p, const VertexNumbers& u,
                           PathResult& result, const VertexShading& vs, const BsdfSample& bs,
                           BatchRay& bounce) {
  VertexRays rays = vs.rays;
  if (!bs.valid()) return rays;
  const glm::vec3 wi = vs.frame.toWorld(bs.wi);
  if (!sameSide(wi, p.hit, bs.wi)) return rays;
  if (vs.splitsHere) p.share = diffuseShare(bs);
  if (p.depth == 0 && p.record) {
    p.record->sampled = true;
    p.record->dir = wi;
    p.record->pdf = bs.pdf;
    p.weight0 = bs.weight;
  }
  p.beta *= bs.weight;
  // Whether the path ends at what this ray finds: the bounce cap, or Russian roulette
  // (thesis Algorithm 2: survive with the largest throughput channel, then rescale).
  // Decided before the ray is traced (the same number from this vertex's sampler as
  // after), so that a last hit is rebuilt only as far as its emission needs.
  p.last = int(p.depth) >= ctx.settings.maxBounces;
  p.survival = 1.0f;
  if (!p.last && int(p.depth) + 1 >= ctx.settings.russianRouletteDepth) {
    p.survival = std::min(1.0f, std::max(p.beta.r, std::max(p.beta.g, p.beta.b)));
    p.last = !(u.roulette < p.survival);
  }
  // Through a volume's surface the path enters or leaves its medium.
  if (glm::dot(wi, p.hit.geometricNormal) < 0.0f && volumeMaterial(ctx.scene, p.hit.instance)) {
    if (p.hit.frontFace)
      p.media.enter(p.hit.instance);
    else
      p.media.leave(p.hit.instance);
  }
  p.wi = wi;
  p.bsdfPdf = bs.pdf;
  bounce.set(offsetRayOrigin(p.hit, wi), wi, 0.0f, kInfinity);
  ++result.rays;
  rays.bounce = true;
  return rays;
}

VertexRays shadeVertex(const TraceContext& ctx, PathState& p, const VertexNumbers& u,
                       PathResult& result, ShadowRay& shadow, BatchRay& bounce) {
  VertexShading vs;
  drawLight(ctx, p, u, vs);
  startVertex(p, result, vs);
  prepareVertex(p.hit.bsdf, vs);
  shadeSpecularAlbedo(p, vs, result);
  if (!shadeVertexHead(ctx, p, u, result, shadow, vs)) return vs.rays;
  return shadeVertexTail(ctx, p, u, result, vs, sampleBsdf(vs.bsdf, u.bsdf), bounce);
}

bool finishReusedSample(const TraceContext& ctx, const SurfaceHit& hit, const glm::vec3& wo,
                        const FirstBounce& reuse, PathResult& result) {
  PathState p = startPath(hit, wo, {}, nullptr, &reuse);
  ShadowRay shadow;
  BatchRay bounce;
  const VertexRays rays = shadeVertex(ctx, p, reuse.numbers, result, shadow, bounce);
  if (rays.shadow || rays.bounce) return false;
  finishPath(p, result);
  return true;
}

void resolveShadow(PathState& p, PathResult& result, const ShadowRay& shadow, bool blocked) {
  // Read before the record is written, which might alias them for all the compiler knows:
  // where directLight has just stored them (a reused sample's, answered by the left's
  // shadow), they are taken from registers instead of loads that stalled on store
  // forwarding (a fifth of shadeVertexHead's time, perf annotate).
  const glm::vec3 diffuse = shadow.diffuse, specular = shadow.specular;
  if (p.record && p.depth == 0) {
    p.record->shadowTraced = true;
    p.record->shadowBlocked = blocked;
  }
  if (blocked) return;
  result.diffuse += diffuse;
  result.specular += specular;
}

namespace {

static_assert(std::is_trivially_destructible_v<SurfaceHit>);  // built over in place below

// advancePath once the bounce's hit 'next' is built: what it absorbs and emits, and the
// record. 'from': the position of the vertex the bounce left (p.hit may be 'next' already).
void arriveAt(const TraceContext& ctx, PathState& p, PathResult& result, const TraceHit& th,
              SurfaceHit& next, const glm::vec3& from) {
  if (th.hit) {
    absorbAlong(ctx.scene, p, th, next, p.beta);
    // Inside another medium an interface bends light by the two media's ratio.
    if (p.media.size > 0 && next.bsdf.eta > 0.0f && volumeMaterial(ctx.scene, th.instance))
      next.bsdf.eta = relativeEta(ctx.scene, p.media, th.instance, next.frontFace);
  }
  const FoundLight found = foundLight(ctx, from, th, th.hit ? &next : nullptr, p.wi);
  addSplit(result, p.beta * found.weighted(p.bsdfPdf), p.share);
  if (p.depth == 0 && p.record) recordSecondVertex(p, result, th, next, found);
}

}  // namespace

bool advancePath(const TraceContext& ctx, PathState& p, PathResult& result, const TraceHit& th,
                 const HitGeometry& geometry) {
  const HitRef ref{th.instance, th.triangle, th.b1, th.b2};
  const glm::vec3 from = p.hit.position;
  if (!th.hit || p.last) {  // the path ends here; p.hit stays its last vertex (finishPath's)
    SurfaceHit end = !th.hit ? SurfaceHit{} : surfaceEmissionAt(ctx.scene, ref, geometry, p.wi);
    arriveAt(ctx, p, result, th, end, from);
    return false;
  }
  // Read before p.hit goes; only while lightTracedCaustic can still ask, so that a path
  // without caustics pays nothing per bounce.
  if (ctx.settings.caustics && int(p.depth) < kCausticReceivers)
    p.receiversBefore = p.receiversBefore && causticReceiver(p.hit.bsdf);
  // The next vertex is built in p.hit itself. Built on the stack and assigned, its ~150
  // bytes were copied per bounce, read in 16-byte loads across the callee's narrower
  // stores, which stalled on store forwarding (a quarter of advancePath's time, perf).
  ::new (static_cast<void*>(&p.hit))
      SurfaceHit(surfaceAt(ctx.scene, ctx.embree.materials(), ref, geometry, p.wi));
  arriveAt(ctx, p, result, th, p.hit, from);
  p.beta /= p.survival;
  p.wo = -p.wi;
  ++p.depth;
  return true;
}

void finishPath(const PathState& p, PathResult& result) {
  if (!p.albedoSet) result.albedo = p.hit.bsdf.baseColor;
  if (!finite(result.diffuse) || !finite(result.specular)) {
    result.diffuse = result.specular = glm::vec3(0.0f);
    result.rejected = 1;
    if (p.record) p.record->sampled = false;
  }
  if (p.record && p.record->sampled) {
    const glm::vec3 after = result.diffuse + result.specular - p.before0;
    p.record->beyond = divideOrZero(after, p.weight0);
  }
  result.radiance = result.diffuse + result.specular;
}

// The scalar form of the batched tracer's loop: one path, each ray traced as it is made.
PathResult continuePath(const TraceContext& ctx, const SurfaceHit& start, const glm::vec3& wo,
                        SampleCounters counters) {
  PathResult result;
  PathState path = startPath(start, wo, counters);
  for (;;) {
    ShadowRay shadow;
    BatchRay bounce;
    const VertexNumbers u =
        drawVertexNumbers(path.sampler, path.depth, vertexDraws(ctx, path.depth));
    const VertexRays rays = shadeVertex(ctx, path, u, result, shadow, bounce);
    if (rays.shadow) {
      const BatchRay& r = shadow.ray;
      resolveShadow(path, result, shadow, ctx.embree.occluded(r.origin, r.dir, r.tnear, r.tfar));
    }
    if (!rays.bounce) break;
    const TraceHit th = ctx.embree.intersect(bounce.origin, bounce.dir, bounce.tnear, bounce.tfar);
    const HitGeometry geometry =
        th.hit ? hitGeometry(ctx.scene, {th.instance, th.triangle, th.b1, th.b2}) : HitGeometry{};
    if (!advancePath(ctx, path, result, th, geometry)) break;
  }
  finishPath(path, result);
  return result;
}

}  // namespace photovr
