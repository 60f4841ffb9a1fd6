// The batched (wavefront) tracer: many paths advance one bounce at a time, each stage over
// the whole batch before the next (Laine, Karras & Aila, "Megakernels Considered Harmful:
// Wavefront Path Tracing on GPUs", HPG 2013, in its CPU form), so that Embree gets every
// shadow ray and every bounce ray of a bounce in one call, and each stage's code and data
// stay in cache while it runs over the batch. Per path, the steps are trace/path_stages.h's:
// a path's result equals continuePath's for the same counters whenever Embree answers its
// rays alike (bit for bit here: tests/trace/wavefront_test.cpp).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "trace/bsdf_stage.h"
#include "trace/path_stages.h"
#include "trace/path_tracer.h"
#include "trace/split_lanes.h"

namespace photovr {

// Where one path starts: a surface hit seen along -wo, and its sample counters.
struct PathStart {
  SurfaceHit hit;
  glm::vec3 wo{0.0f};
  SampleCounters counters;
  FirstBounce* record = nullptr;  // stereo reuse: see PathState
  const FirstBounce* reuse = nullptr;
};

// The batch's working memory, kept by each tracing thread from batch to batch.
struct WavefrontScratch {
  std::vector<PathState> paths;        // continuePaths' from PathStarts
  std::vector<uint32_t> active, next;  // paths still going, by index
  std::vector<PathSampler> samplers;   // the active paths' samplers ...
  std::vector<VertexNumbers> numbers;  // ... and the numbers their vertices draw
  // Per active path, its vertex up to the BSDF sample and how that sample is drawn; the
  // vertices sampled in lanes, their numbers and samples, in the active paths' order.
  enum class Sampling : uint8_t { None, Lanes, One };
  std::vector<VertexShading> shading;
  std::vector<BrdfPrepareJob> prepareJobs;
  std::vector<SplitJob> splitJobs;  // reused samples' splits answered in lanes
  std::vector<Sampling> sampling;
  std::vector<const BsdfVertex*> laneVertices;
  std::vector<glm::vec2> laneNumbers;
  std::vector<BsdfSample> laneSamples;
  std::vector<ShadowRay> shadows;     // this bounce's shadow rays ...
  std::vector<uint32_t> shadowOwner;  // ... and the path each belongs to
  std::vector<BatchRay> shadowRays;
  std::vector<BatchRayHit> bounceRays;  // this bounce's bounce rays and hits ...
  std::vector<uint32_t> bounceOwner;    // ... and the path each belongs to
  std::vector<TraceHit> found;          // per bounce ray, what it found
  std::vector<HitRef> hits;             // the bounce rays' hits ...
  std::vector<HitGeometry> geometry;    // ... their geometry ...
  std::vector<uint32_t> hitOf;          // ... and, per bounce ray, its hit's index (~0u: none)
};

// This thread's scratch (thread_local: TBB tasks of one thread run one at a time).
WavefrontScratch& threadScratch();

// finishReusedSample for a batch of reused right samples, each paths[i] = startPath(hit, wo,
// {}, nullptr, &reuse): done[i] and results[i] as finishReusedSample gives them, to the bit,
// with the BSDF stage's first half in lanes (trace/bsdf_stage.h). paths[i] is left as the
// head left it; a sample not done is to be continued as a path from its start.
void finishReusedSamples(const TraceContext& ctx, std::span<PathState> paths,
                         std::span<PathResult> results, std::span<uint8_t> done,
                         WavefrontScratch& scratch);

// continuePath for every start, results[i] for starts[i]; results.size() == starts.size().
void continuePaths(const TraceContext& ctx, std::span<const PathStart> starts,
                   std::span<PathResult> results, WavefrontScratch& scratch);
// The same for paths already started (startPath), advanced where they are: PathBatcher
// builds its paths in place, with no start and no state copied (scratch.paths unused).
void continuePaths(const TraceContext& ctx, std::span<PathState> paths,
                   std::span<PathResult> results, WavefrontScratch& scratch);

}  // namespace photovr
