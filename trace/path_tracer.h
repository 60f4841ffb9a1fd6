// The path tracer (thesis Algorithm 2, with NEE + MIS for lights that have area): one
// function continues a path from a surface hit — the pure path tracer and the hybrid both
// call it — and a renderer traces primary rays through an EyeCamera's jittered samples.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/scene.h"
#include "trace/embree_scene.h"
#include "trace/lights.h"
#include "trace/rng.h"
#include "trace/stereo_reuse.h"
#include "trace/surface.h"

namespace photovr {

struct TraceSettings {
  int samplesPerPixel = 1;
  int maxBounces = 8;            // indirect bounces after the first hit (--bounces)
  int russianRouletteDepth = 5;  // thesis Algorithm 2: roulette from depth 5
  uint32_t seed = 0;
  SamplerKind sampler = SamplerKind::Sobol;  // --sampler
  BatchCall batchCall = BatchCall::Stream;   // how the batched tracer hands rays to Embree
  bool stereoReuse = false;  // a stereo frame's second eye reuses the first's (--stereo-reuse)
  // Stereo reuse: every reused sample traces its own NEE shadow ray instead of taking the
  // left's answer (trace/stereo_reuse.h, "The approximations"): that approximation off, to
  // measure it (bench/bench_stereo.cpp, tests/trace/stereo_reuse_test.cpp).
  bool reusedOwnShadowRays = false;
  // Directional lights' caustics by light tracing (trace/caustics.h, --caustics): the
  // paths it takes are left out of next-event estimation.
  bool caustics = false;
  WorkSkips skips;  // work the scene does not need (work_skips.h); the renderers build
                    // their EmbreeScene and LightSet with the same skips
};

// Everything a path needs, built once per scene.
struct TraceContext {
  const Scene& scene;
  const EmbreeScene& embree;
  const LightSet& lights;
  TraceSettings settings;
};

// Whether a right sample reusing 'partner' (a record of 'role.reuse'; null: none) traces its
// own shadow ray instead of taking the partner's answer: at the edge of a punctual light's
// shadow (leftShadowEdge), or everywhere with TraceSettings::reusedOwnShadowRays.
inline bool tracesOwnShadowRay(const TraceSettings& s, const StereoRole& role,
                               const FirstBounce* partner) {
  return partner && (s.reusedOwnShadowRays || leftShadowEdge(*role.reuse, *partner));
}

struct PathResult {
  // Provided, as PathState's (trace/path_stages.h): with the implicit one, GCC zeroed a
  // result with `rep stosq`, which no later load of it can take its value from, so the
  // path's first sums waited for the string store to finish (store forwarding).
  PathResult() {}

  glm::vec3 radiance{0.0f};  // reflected radiance towards wo (emission of the start excluded)
  // The denoiser's lobes (radiance = diffuse + specular): the part reflected by the diffuse
  // lobe of the path's denoiser surface (the start, or where a path through a smooth mirror
  // or glass start first meets another surface: trace/path_stages.h) ...
  glm::vec3 diffuse{0.0f};
  glm::vec3 specular{0.0f};  // ... and the rest: specular lobes, what the mirror or glass adds
  // Their demodulation albedos: the denoiser surface's diffuse albedo times the throughput
  // up to it (0 when the path found none), and the start's split-sum specular albedo.
  glm::vec3 diffuseAlbedo{0.0f}, specularAlbedo{0.0f};
  glm::vec3 albedo{0.0f};  // base colour of the first non-mirror-like vertex (denoiser AOV)
  // The denoiser surface's guide when it is not the start (primary surface replacement):
  // its shading normal scaled by its instance + 1; 0 when the start is the denoiser surface.
  glm::vec3 guide{0.0f};
  uint32_t rejected = 0;    // samples dropped because they were NaN/Inf
  uint32_t rays = 0;        // bounce and shadow rays traced
  uint32_t ownBounces = 0;  // stereo reuse: 1 if a reused right sample traced its own bounce
};

// Radiance leaving 'hit' towards 'wo' (unit, pointing away from the surface), from every
// path continuing there: NEE at each vertex, BSDF sampling, MIS, Russian roulette.
PathResult continuePath(const TraceContext& ctx, const SurfaceHit& hit, const glm::vec3& wo,
                        SampleCounters counters);

// One eye's image. Rows bottom-up, as GL stores them (row 0 is the lowest).
struct EyeImage {
  int width = 0, height = 0;
  std::vector<glm::vec3> color;   // mean radiance over the samples
  std::vector<glm::vec3> albedo;  // AOVs of the primary hit
  std::vector<glm::vec3> normal;
  std::vector<float> depth;       // reversed-Z, as the G-buffer's
  std::vector<uint32_t> samples;  // samples taken per pixel
  // Denoiser inputs (filled by the hybrid; empty where a renderer does not produce them):
  // each lobe's mean radiance divided by its albedo, and those albedos.
  std::vector<glm::vec3> diffuse, specular, diffuseAlbedo, specularAlbedo;
  // ... and the edge-stopping guide of pixels whose first path looked through a smooth
  // mirror or glass (PathResult::guide; 0 elsewhere: the G-buffer's guides hold there).
  std::vector<glm::vec3> guide;
  uint64_t rays = 0;              // rays traced (primary, bounce, shadow)
  uint64_t paths = 0;             // paths continued from a primary hit ...
  uint64_t reusedPaths = 0;       // ... of which reused the left eye's (trace/stereo_reuse.h)
  uint64_t reusedOwnBounces = 0;  // ... of which traced an own bounce too (ReuseSplit)
  uint64_t rejectedSamples = 0;   // NaN/Inf samples caught and dropped
  // Light-traced caustics (trace/caustics.h), part of the tracer's time: how long (the
  // frame's light paths where this eye traced them, and their connections to it) and how
  // many of their receivers landed on one of its pixels (a path has up to kCausticReceivers).
  double causticMs = 0.0;
  uint64_t causticSplats = 0;
  size_t index(int x, int y) const { return size_t(y) * width + x; }
};

// Pure path tracing of one eye. Sample s of the frame sits at the sampler's pixel position
// for index frame * spp + s (core/camera.h, samplePosition), not at camera.jitter: at one
// sample per frame the two agree when the camera was made with samplePosition(kind, frame),
// as the rasterizer's is. 'reuse': an earlier frame's image, done with, to trace into
// instead of fresh memory (whose first touch costs ~300 ms per 960x1080 image here,
// docs/ARCHITECTURE.md, "Memory reuse"), as the hybrid's. 'stereo': this eye's part in
// stereo path reuse (trace/stereo_reuse.h).
EyeImage renderPathTraced(const TraceContext& ctx, const EyeCamera& camera, uint32_t eye,
                          uint32_t frame, EyeImage reuse = {}, StereoRole stereo = {});

}  // namespace photovr
