#include "trace/wavefront.h"

#include "trace/bsdf_lanes.h"
#include "trace/scratch.h"

namespace photovr {
namespace {

using Sampling = WavefrontScratch::Sampling;

// Sampling stage: the numbers of every active path's vertex, in one vectorised pass (all
// active paths are at the same depth: they start together and advance a bounce a step).
void drawAll(const TraceContext& ctx, std::span<const PathState> paths, WavefrontScratch& s) {
  const size_t n = s.active.size();
  s.samplers.resize(n);
  s.numbers.resize(n);
  for (size_t j = 0; j < n; ++j) s.samplers[j] = paths[s.active[j]].sampler;
  const uint32_t depth = paths[s.active[0]].depth;
  drawBatchNumbers(s.samplers, depth, vertexDraws(ctx, depth), s.numbers);
}

// A prepare job for the lanes, written in place: one built on the stack and copied in
// stalled on store forwarding (a third of continuePaths' own time).
void queuePrepare(const BsdfParams& params, VertexShading& vs, bool reused, WavefrontScratch& s) {
  BrdfPrepareJob& job = s.prepareJobs.emplace_back();
  job.params = &params;
  job.wo = vs.wo;
  job.wi = vs.wiL;
  job.vertex = &vs.bsdf;
  job.eval = &vs.nee;
  if (!reused) return;
  job.wi2 = vs.wiReused;
  job.eval2 = &vs.reused;
}

// Shading stage: every active path's vertex, in six passes: each vertex's light sample for
// NEE (a loop of its own: trace/path_stages.h, drawLight), its start (its frame and the
// light's place in it), the BSDF stage's first half (every vertex without glass or
// layers prepared, and evaluated towards its light, in SIMD lanes: trace/bsdf_lanes.h),
// each vertex's head (NEE's shadow ray, stereo reuse), the second half (their BSDFs
// sampled in lanes), then each vertex's bounce ray. Glass and layered vertices take the
// scalar steps in the same passes. Rays are written in place into their queue (dropped
// again where the vertex made none) and the shadow rays copied into Embree's array after
// the loop: a ray copied right after the scalar stores that built it stalled on store
// forwarding.
void shadeAll(const TraceContext& ctx, std::span<PathState> paths, std::span<PathResult> results,
              WavefrontScratch& s) {
  s.shadows.clear(), s.shadowOwner.clear(), s.shadowRays.clear();
  s.bounceRays.clear(), s.bounceOwner.clear();
  s.prepareJobs.clear(), s.laneVertices.clear(), s.laneNumbers.clear();
  drawAll(ctx, paths, s);
  const size_t n = s.active.size();
  growTo(s.shading, n);
  growTo(s.sampling, n);
  for (size_t j = 0; j < n; ++j) drawLight(ctx, paths[s.active[j]], s.numbers[j], s.shading[j]);
  for (size_t j = 0; j < n; ++j) {
    const uint32_t k = s.active[j];
    VertexShading& vs = s.shading[j];
    startVertex(paths[k], results[k], vs);
    const BsdfParams& params = paths[k].hit.bsdf;
    // A reused right sample that needs a ray is rare here (finishReusedSamples takes the
    // others): its second direction is evaluated one by one.
    if (plainBsdf(params) && !vs.reusing)
      queuePrepare(params, vs, false, s);
    else
      prepareVertex(params, vs);
  }
  prepareBrdfs(s.prepareJobs);
  if (paths[s.active[0]].depth == 0)
    for (size_t j = 0; j < n; ++j)
      shadeSpecularAlbedo(paths[s.active[j]], s.shading[j], results[s.active[j]]);
  for (size_t j = 0; j < n; ++j) {
    const uint32_t k = s.active[j];
    ShadowRay& shadow = s.shadows.emplace_back();
    VertexShading& vs = s.shading[j];
    const bool bounces = shadeVertexHead(ctx, paths[k], s.numbers[j], results[k], shadow, vs);
    if (vs.rays.shadow)
      s.shadowOwner.push_back(k);
    else
      s.shadows.pop_back();
    s.sampling[j] = !bounces             ? Sampling::None
                    : plainBrdf(vs.bsdf) ? Sampling::Lanes
                                         : Sampling::One;
    if (s.sampling[j] == Sampling::Lanes) {
      s.laneVertices.push_back(&vs.bsdf);
      s.laneNumbers.push_back(s.numbers[j].bsdf);
    }
  }
  for (const ShadowRay& shadow : s.shadows) s.shadowRays.push_back(shadow.ray);
  s.laneSamples.resize(s.laneVertices.size());
  sampleBrdfs(s.laneVertices, s.laneNumbers, s.laneSamples);
  size_t lane = 0;
  for (size_t j = 0; j < n; ++j) {
    if (s.sampling[j] == Sampling::None) continue;
    const uint32_t k = s.active[j];
    const VertexShading& vs = s.shading[j];
    const BsdfSample bs = s.sampling[j] == Sampling::Lanes ? s.laneSamples[lane++]
                                                           : sampleBsdf(vs.bsdf, s.numbers[j].bsdf);
    BatchRay& bounce = s.bounceRays.emplace_back().ray;
    if (shadeVertexTail(ctx, paths[k], s.numbers[j], results[k], vs, bs, bounce).bounce)
      s.bounceOwner.push_back(k);
    else
      s.bounceRays.pop_back();
  }
}

void traceShadows(const TraceContext& ctx, std::span<PathState> paths,
                  std::span<PathResult> results, WavefrontScratch& s) {
  const size_t n = s.shadowRays.size();
  ctx.embree.occludedBatch(s.shadowRays.data(), n, ctx.settings.batchCall);
  for (size_t j = 0; j < n; ++j) {
    const uint32_t k = s.shadowOwner[j];
    resolveShadow(paths[k], results[k], s.shadows[j], s.shadowRays[j].blocked());
  }
}

// Bounce stage: traces the bounce rays, then moves each path to what its ray found; the
// paths that go on are the next bounce's active set.
// Geometry stage: every bounce hit's position, error bound and normal in one vectorised pass
// (trace/hit_geometry.h); s.hitOf[j] indexes bounce ray j's, or is ~0u for a miss.
// s.found[j] is bounce ray j's answer, kept for advancePath: a TraceHit made on the stack
// right before the call that reads it stalled on store forwarding there. Here each field
// is written from the ray's own: a TraceHit built and then copied went through the stack
// in 8-byte stores read back by a 16-byte load, which stalled too (a fifth of
// continuePaths' own time on cornell, perf annotate).
void rebuildGeometry(const TraceContext& ctx, WavefrontScratch& s) {
  const size_t n = s.bounceRays.size();
  s.hits.clear();
  s.hitOf.resize(n);
  s.found.resize(n);
  for (size_t j = 0; j < n; ++j) {
    const BatchRayHit& r = s.bounceRays[j];
    TraceHit& th = s.found[j];
    if (r.geomID == ~0u) {
      th = TraceHit{};
      s.hitOf[j] = ~0u;
      continue;
    }
    const uint32_t instance = r.instance();
    th.hit = true, th.t = r.ray.tfar, th.instance = instance, th.triangle = r.primID;
    th.b1 = r.u, th.b2 = r.v;
    s.hitOf[j] = uint32_t(s.hits.size());
    s.hits.push_back({instance, r.primID, r.u, r.v});
  }
  s.geometry.resize(s.hits.size());
  hitGeometries(ctx.scene, s.hits, s.geometry);
}

void traceBounces(const TraceContext& ctx, std::span<PathState> paths,
                  std::span<PathResult> results, WavefrontScratch& s) {
  const size_t n = s.bounceRays.size();
  ctx.embree.intersectBatch(s.bounceRays.data(), n, ctx.settings.batchCall);
  rebuildGeometry(ctx, s);
  s.next.clear();
  for (size_t j = 0; j < n; ++j) {
    const uint32_t k = s.bounceOwner[j];
    // By reference: a conditional with HitGeometry{} in it copied the hit's geometry into a
    // temporary (a third of continuePaths' own time waited on that copy).
    static const HitGeometry kMiss{};
    const HitGeometry& g = s.hitOf[j] == ~0u ? kMiss : s.geometry[s.hitOf[j]];
    if (advancePath(ctx, paths[k], results[k], s.found[j], g)) s.next.push_back(k);
  }
  s.active.swap(s.next);
}

// The reused samples' splits where the vertex has neither glass nor layers: a whole split
// here, the others in lanes (trace/split_lanes.h); the rest the head answers one by one.
// (The head had asked reusesWhole again for each whole split, a libm cosf among it.)
void answerSplits(std::span<PathState> paths, WavefrontScratch& s) {
  s.splitJobs.clear();
  for (size_t i = 0; i < paths.size(); ++i) {
    const PathState& p = paths[i];
    VertexShading& vs = s.shading[i];
    if (!plainBsdf(p.hit.bsdf)) continue;
    vs.splitAnswered = true;
    if (reusesWhole(*p.reuse, p.hit, vs.bsdf, p.wo)) {
      vs.split = answerWholeSplit(p, vs);
      continue;
    }
    // In place: a job built on the stack and copied in waited on store forwarding (a sixth
    // of finishReusedSamples' own time).
    SplitJob& job = s.splitJobs.emplace_back();
    job.left = p.reuse;
    job.right = &vs.bsdf;
    job.frame = &vs.frame;
    job.geometricNormal = p.hit.geometricNormal;
    job.reusing = vs.reusing;
    job.pdfTowardsLeft = vs.reused.pdf;
    job.u = p.reuse->numbers.bsdf;
    job.out = &vs.split;
  }
  splitAnswers(s.splitJobs);
}

}  // namespace

WavefrontScratch& threadScratch() {
  thread_local WavefrontScratch scratch;
  return scratch;
}

void finishReusedSamples(const TraceContext& ctx, std::span<PathState> paths,
                         std::span<PathResult> results, std::span<uint8_t> done,
                         WavefrontScratch& s) {
  const size_t n = paths.size();
  growTo(s.shading, n);
  s.prepareJobs.clear();
  for (size_t i = 0; i < n; ++i) drawLight(ctx, paths[i], paths[i].reuse->numbers, s.shading[i]);
  for (size_t i = 0; i < n; ++i) {
    VertexShading& vs = s.shading[i];
    results[i] = PathResult{};
    startVertex(paths[i], results[i], vs);
    const BsdfParams& params = paths[i].hit.bsdf;
    if (plainBsdf(params))
      queuePrepare(params, vs, vs.reusing, s);
    else
      prepareVertex(params, vs);
  }
  prepareBrdfs(s.prepareJobs);
  for (size_t i = 0; i < n; ++i) shadeSpecularAlbedo(paths[i], s.shading[i], results[i]);
  answerSplits(paths, s);
  for (size_t i = 0; i < n; ++i) {
    PathState& p = paths[i];
    const VertexNumbers& u = p.reuse->numbers;  // the head may drop p.reuse
    ShadowRay shadow;
    VertexShading& vs = s.shading[i];
    const bool bounces = shadeVertexHead(ctx, p, u, results[i], shadow, vs);
    done[i] = !bounces && !vs.rays.shadow;
    if (done[i]) finishPath(p, results[i]);
  }
}

void continuePaths(const TraceContext& ctx, std::span<PathState> paths,
                   std::span<PathResult> results, WavefrontScratch& s) {
  const size_t n = paths.size();
  s.active.resize(n);
  for (size_t k = 0; k < n; ++k) {
    results[k] = PathResult{};
    s.active[k] = uint32_t(k);
  }
  while (!s.active.empty()) {
    shadeAll(ctx, paths, results, s);
    traceShadows(ctx, paths, results, s);
    traceBounces(ctx, paths, results, s);
  }
  for (size_t k = 0; k < n; ++k) finishPath(paths[k], results[k]);
}

void continuePaths(const TraceContext& ctx, std::span<const PathStart> starts,
                   std::span<PathResult> results, WavefrontScratch& s) {
  const size_t n = starts.size();
  s.paths.clear();
  s.paths.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const PathStart& st = starts[k];
    startPath(s.paths[k], st.hit, st.wo, st.counters, st.record, st.reuse);
  }
  continuePaths(ctx, std::span<PathState>(s.paths), results, s);
}

}  // namespace photovr
