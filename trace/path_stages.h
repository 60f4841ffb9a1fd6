// The steps of one path, each a function of the path's state alone, so that a scalar loop
// (continuePath, the test reference) and the batched tracer (trace/wavefront.h) run the
// same code and draw the same numbers: a path's result does not depend on how many other
// paths travel with it, only on the ray answers Embree gives it.
//
// One bounce is shadeVertex (NEE and BSDF sampling at the current vertex: a shadow ray and
// a bounce ray to trace), resolveShadow (the shadow ray's answer), advancePath (the bounce
// ray's answer: found light, the next vertex or the end).
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "trace/bsdf.h"
#include "trace/embree_scene.h"
#include "trace/lights.h"
#include "trace/media.h"
#include "trace/path_tracer.h"
#include "trace/rng.h"
#include "trace/sampling.h"
#include "trace/stereo_reuse.h"
#include "trace/surface.h"
#include "trace/vertex_numbers.h"

namespace photovr {

// A path between bounces.
struct PathState {
  // Every member has its initialiser. Provided, so that a batch's emplace_back() (value-
  // initialisation) only runs them: with the implicit constructor GCC zero-filled the whole
  // state first (a `rep stos` of 288 bytes, a third of PathBatcher::addHit's time).
  PathState() {}

  SurfaceHit hit;  // the current vertex
  glm::vec3 wo{0.0f};
  glm::vec3 beta{1.0f};  // throughput up to the current vertex
  // The denoiser's lobes are split at the path's denoiser surface: its first vertex, or,
  // when that is a smooth mirror or glass with no diffuse lobe (seesThrough), the first
  // vertex beyond it that is not. Light gathered before it is specular; at it, NEE splits
  // by the lobes' values and the bounce by 'share', its diffuse fraction, which every later
  // vertex's light keeps. So what a glass ball shows is demodulated and filtered as the
  // surfaces it shows, not as the glass (docs/ARCHITECTURE.md, "Denoiser").
  glm::vec3 share{0.0f};
  PathSampler sampler;
  uint32_t depth = 0;
  bool split = false;  // the denoiser surface is the current vertex or behind the path
  // Every vertex before the current one is a causticReceiver (trace/caustics.h): with
  // caustics on, and no more than kCausticReceivers of them, the current vertex's NEE
  // towards a directional light leaves a caster's specular lobe to the light tracer.
  bool receiversBefore = true;
  bool albedoSet = false;
  // The bounce ray shadeVertex chose, for advancePath.
  glm::vec3 wi{0.0f};
  float bsdfPdf = 0.0f;
  float survival = 1.0f;  // Russian roulette's survival probability (1: no roulette)
  bool last = false;      // the path ends at what the bounce ray finds
  MediumStack media;      // the volumes the path is inside (the bounce ray's medium)
  // Stereo reuse (trace/stereo_reuse.h): the left eye's path records its first bounce in
  // 'record'; a right eye's path that reuses 'reuse' stops after its first vertex.
  FirstBounce* record = nullptr;
  const FirstBounce* reuse = nullptr;
  bool ownShadowRay = false;  // reuse: it traces its own shadow ray (tracesOwnShadowRay)
  glm::vec3 weight0{0.0f};    // record: the first bounce's throughput f cos / pdf ...
  glm::vec3 before0{0.0f};    // ... and the radiance gathered up to and with Le(x2)
};

// A shadow ray and what it adds to the path's lobes if nothing blocks it.
struct ShadowRay {
  BatchRay ray;
  glm::vec3 diffuse{0.0f}, specular{0.0f};
};

// What shadeVertex asks to trace.
struct VertexRays {
  bool shadow = false;  // 'shadow' was filled
  bool bounce = false;  // 'bounce' was filled; false: the path ends after the shadow ray
};

// 'record', 'reuse': see PathState (at most one of them).
PathState startPath(const SurfaceHit& hit, const glm::vec3& wo, const SampleCounters& counters,
                    FirstBounce* record = nullptr, const FirstBounce* reuse = nullptr);
// The same into a default-constructed 'path', where it is to travel (a PathState is ~400
// bytes: PathBatcher builds its paths in place instead of copying starts and states).
void startPath(PathState& path, const SurfaceHit& hit, const glm::vec3& wo,
               const SampleCounters& counters, FirstBounce* record = nullptr,
               const FirstBounce* reuse = nullptr);
// startPath for a reused right sample that finishReusedSamples shades at its first vertex:
// without the sampler, as it draws the left's recorded numbers (reuse.numbers); one that
// needs a ray is started again, whole, by startPath. (Copying the sampler was the first read
// of the left's record, and half of startPath's time waited on it: perf annotate.)
void startReusedSample(PathState& path, const SurfaceHit& hit, const glm::vec3& wo,
                       const FirstBounce& reuse, bool ownShadowRay = false);
// The draws a vertex at 'depth' makes (drawVertexNumbers, drawBatchNumbers).
VertexDraws vertexDraws(const TraceContext& ctx, uint32_t depth);
// 'u': the vertex's numbers, drawVertexNumbers(path.sampler, path.depth, vertexDraws(...)).
VertexRays shadeVertex(const TraceContext& ctx, PathState& path, const VertexNumbers& u,
                       PathResult& result, ShadowRay& shadow, BatchRay& bounce);

// shadeVertex in steps around its BSDF, so that the batched tracer prepares, evaluates and
// samples the BSDFs of a whole bounce at once (trace/bsdf_lanes.h): drawLight (NEE's light
// sample), startVertex (the albedos, the frame, the light in it), prepareVertex (the BSDF,
// and its value and pdf towards the light and a reused bounce's direction), shadeVertexHead
// (NEE's shadow ray, stereo reuse's term) returns whether the vertex goes on to a bounce
// ray; if so, shadeVertexTail takes sampleBsdf(vs.bsdf, u.bsdf) and makes it. shadeVertex is
// the steps in that order.
struct VertexShading {
  Frame frame;
  glm::vec3 wo{0.0f};  // in the shading frame
  LightSample light;   // NEE's, with its direction in the shading frame ...
  glm::vec3 wiL{0.0f};
  bool lit = false;  // ... valid and on the side the frame says: nee holds the BSDF there
  // Stereo reuse: the left path's bounce direction in this vertex's frame, where it has one
  // to reuse, and the BSDF's value and pdf there (reuseBounce).
  bool reusing = false;
  glm::vec3 wiReused{0.0f};
  BsdfVertex bsdf;
  BsdfEval nee, reused;
  VertexRays rays;  // the head's shadow ray
  bool splitsHere = false;
  // A reused right sample's split, where a batch answered it before the head (splitAnswers);
  // else the head answers it itself.
  bool splitAnswered = false;
  SplitAnswers split;
};
// NEE's light sample at the path's vertex (vs.light), the step before startVertex. A loop
// of its own in a batch: inside startVertex, an area light's sample (its square root and the
// divisions by the distance that wait on it) was a latency chain the out-of-order core could
// not overlap with the next vertex (sampleTriangle, 6 % of cornell's tracer, stalled on its
// divisions, perf annotate).
void drawLight(const TraceContext& ctx, const PathState& path, const VertexNumbers& u,
               VertexShading& vs);
void startVertex(PathState& path, PathResult& result, VertexShading& vs);
void prepareVertex(const BsdfParams& params, VertexShading& vs);
// A first vertex's specular albedo (the denoiser's demodulation), from its prepared BSDF;
// nothing at later depths. A step of its own between prepareVertex and shadeVertexHead, so
// that a batch runs it in a loop of its own: inside the head, its envBrdfApprox and exp2f
// chain was a latency the out-of-order core could not overlap with the next vertex
// (two fifths of specularAlbedo's time stalled on its result, perf annotate).
void shadeSpecularAlbedo(const PathState& path, const VertexShading& vs, PathResult& result);
bool shadeVertexHead(const TraceContext& ctx, PathState& path, const VertexNumbers& u,
                     PathResult& result, ShadowRay& shadow, VertexShading& vs);
// A reused right sample's split at its first vertex (path.reuse set; vs prepared): what
// shadeVertexHead asks, and trace/split_lanes.h answers for a batch.
SplitAnswers answerSplit(const PathState& path, const VertexShading& vs, const VertexNumbers& u);
// answerSplit where reusesWhole holds: every direction is the reused term's.
SplitAnswers answerWholeSplit(const PathState& path, const VertexShading& vs);
VertexRays shadeVertexTail(const TraceContext& ctx, PathState& path, const VertexNumbers& u,
                           PathResult& result, const VertexShading& vs, const BsdfSample& bs,
                           BatchRay& bounce);
// A reused right sample (startPath's 'reuse') at its first vertex, shaded where it is made,
// with the left's recorded numbers: true with 'result' its finished estimate when it needs no
// ray (the left answered its shadow ray, and its own bounce draws no direction of its own
// term: ~98 % on spheres); false when it does ('result' then partial, to be dropped), and it
// is continued as a path like any other, from the start. So most reused samples never enter
// a batch: no path start, path state or number draws (spheres' right eye 7 % faster,
// docs/MEASUREMENTS.md).
bool finishReusedSample(const TraceContext& ctx, const SurfaceHit& hit, const glm::vec3& wo,
                        const FirstBounce& reuse, PathResult& result);
// The shadow ray's answer: adds what it carries if unblocked; a recording left path keeps
// its first vertex's answer for the right eye (FirstBounce::shadowBlocked).
void resolveShadow(PathState& path, PathResult& result, const ShadowRay& shadow, bool blocked);
// False: the path ended (it left the scene, or 'last' was set). 'geometry': the hit's
// (hitGeometry), when th.hit.
bool advancePath(const TraceContext& ctx, PathState& path, PathResult& result, const TraceHit& th,
                 const HitGeometry& geometry);
// Once the path has ended: the albedo fallback, the NaN/Inf rejection, radiance.
void finishPath(const PathState& path, PathResult& result);

}  // namespace photovr
