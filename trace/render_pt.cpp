// Pure path tracing of an eye image: Embree primary rays through the same jittered pixel
// positions the rasterizer uses, then the wavefront tracer (trace/wavefront.h), in parallel over
// tiles.
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <limits>
#include <span>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include "trace/camera_lanes.h"
#include "trace/caustics.h"
#include "trace/hit_geometry.h"
#include "trace/path_tracer.h"
#include "trace/path_batcher.h"
#include "trace/scratch.h"
#include "trace/standing_lanes.h"

namespace photovr {
namespace {

constexpr int kTile = 16;  // 16 x 16 pixels: enough work per task, many tasks for balance

constexpr float kInfinity = std::numeric_limits<float>::infinity();

static_assert(std::is_trivially_destructible_v<SurfaceHit>);  // built over in place below

struct Counts {
  PathBatcher::Totals traced;  // rays (the primary ones too), rejected samples, own bounces
  uint64_t paths = 0, reused = 0;
};

// The standing pixels (stereo_reuse.h) of a tile's hits (surfaces, in the tile's pixel and
// sample order; standing[k] is surfaces[k]'s), in SIMD lanes (trace/standing_lanes.h), one
// run per sample number: a run shares its offset in the pixel.
void standingPixels(const StereoRole& stereo, const EyeCamera& cam, const CameraRays& camRays,
                    const tbb::blocked_range2d<int>& r, std::span<const BatchRayHit> primary,
                    std::span<const glm::vec2> offsets, std::span<const SurfaceHit> surfaces,
                    std::span<StandingPixel> standing) {
  thread_local std::vector<StandingJob> jobs;
  const size_t spp = offsets.size();
  for (size_t s = 0; s < spp; ++s) {
    jobs.clear();
    size_t j = 0, k = 0;  // primary's index of the next ray, surfaces' of the next hit
    for (int y = r.rows().begin(); y < r.rows().end(); ++y)
      for (int x = r.cols().begin(); x < r.cols().end(); ++x)
        for (size_t t = 0; t < spp; ++t, ++j) {
          if (primary[j].geomID == ~0u) continue;
          if (t == s) jobs.push_back({&surfaces[k], camRays.throughCentre(x, y), &standing[k]});
          ++k;
        }
    standingPixelsOf(windowOf(stereo), cam.pose.position, offsets[s], jobs);
  }
}

// A tile's buffers, kept by its thread from tile to tile.
struct TileScratch {
  std::vector<glm::vec2> offsets;    // sample s's offset in its pixel
  std::vector<glm::vec2> positions;  // each ray's point in the window
  std::vector<glm::vec3> directions;
  std::vector<BatchRayHit> primary;  // pixel by pixel, sample by sample
  std::vector<HitRef> hits;          // the primary rays that hit, in order
  std::vector<HitGeometry> geometry;
  std::vector<SurfaceHit> surfaces;  // hits[k]'s surface at k (grown, never shrunk)
  std::vector<StandingPixel> standing;
};

// Sample s of frame f sits at the sampler's position for index f * spp + s
// (samplePosition): with one sample per frame that is the frame's jitter, where the
// G-buffer samples too; with more, each sample has its own place in the pixel, so one
// frame of N samples antialiases as N frames of one do. The offset is the same in every
// pixel: drawn once a tile, not per pixel (it was 6 % of pt's reusing eye, perf). The
// tile's primary rays go to Embree as one coherent batch.
void traceCameraRays(const TraceContext& ctx, const EyeCamera& cam, const CameraRays& camRays,
                     uint32_t frame, const tbb::blocked_range2d<int>& r, TileScratch& t) {
  const uint32_t spp = uint32_t(ctx.settings.samplesPerPixel);
  t.offsets.resize(spp);
  for (uint32_t s = 0; s < spp; ++s)
    t.offsets[s] = samplePosition(ctx.settings.sampler, frame * spp + s);
  t.positions.clear();
  for (int y = r.rows().begin(); y < r.rows().end(); ++y)
    for (int x = r.cols().begin(); x < r.cols().end(); ++x)
      for (uint32_t s = 0; s < spp; ++s)
        t.positions.push_back(glm::vec2(x + 0.5f, y + 0.5f) + t.offsets[s]);
  t.directions.resize(t.positions.size());
  sampleRays(camRays, t.positions, t.directions);
  t.primary.clear();
  // In place: a ray made on the stack and copied stalled on store forwarding.
  for (const glm::vec3& dir : t.directions)
    t.primary.emplace_back().ray.set(cam.pose.position, dir, 0.0f, kInfinity);
  ctx.embree.intersectBatch(t.primary.data(), t.primary.size(), ctx.settings.batchCall,
                            RayRole::Camera);
}

// The tile's surfaces, built in place: the hits' geometry in one vectorised pass, as the
// wavefront tracer's bounce hits, then each hit's surface. Returns how many rays hit.
size_t buildSurfaces(const TraceContext& ctx, TileScratch& t) {
  t.hits.clear();
  for (const BatchRayHit& h : t.primary)
    if (h.geomID != ~0u) t.hits.push_back({h.traceHit().instance, h.primID, h.u, h.v});
  t.geometry.resize(t.hits.size());
  hitGeometries(ctx.scene, t.hits, t.geometry);
  growTo(t.surfaces, t.hits.size());
  for (size_t k = 0, j = 0; j < t.primary.size(); ++j) {
    if (t.primary[j].geomID == ~0u) continue;
    ::new (static_cast<void*>(&t.surfaces[k])) SurfaceHit(surfaceAt(
        ctx.scene, ctx.embree.materials(), t.hits[k], t.geometry[k], t.primary[j].ray.dir));
    ++k;
  }
  return t.hits.size();
}

// Depth and normal are the first hit's (the G-buffer keeps one surface per pixel too). Where
// the samples look across, every surface's standing pixel in the other eye's window is found
// before any sample is added: a reusing eye's partner records are then asked for ahead of
// their reads (prefetchPartnersAhead), as the hybrid's tiles do (each had been a miss when
// findPartner read it). Then the paths go as batches of the wavefront tracer.
void traceTile(const TraceContext& ctx, const EyeCamera& cam, uint32_t eye, uint32_t frame,
               const StereoRole& stereo, const tbb::blocked_range2d<int>& r, EyeImage& img,
               Counts& counts) {
  const uint32_t spp = uint32_t(ctx.settings.samplesPerPixel);
  const glm::vec3 forward = cam.pose.orientation * glm::vec3(0, 0, -1);
  const CameraRays camRays(cam);
  thread_local TileScratch t;
  thread_local PathBatcher batcher;
  traceCameraRays(ctx, cam, camRays, frame, r, t);
  counts.traced.rays += t.primary.size();
  const size_t hitCount = buildSurfaces(ctx, t);
  const std::span<const SurfaceHit> surfaces = std::span(t.surfaces).first(hitCount);
  growTo(t.standing, stereo.looksAcross() ? hitCount : 0);
  const std::span<StandingPixel> standing =
      std::span(t.standing).first(stereo.looksAcross() ? hitCount : 0);
  if (stereo.looksAcross())
    standingPixels(stereo, cam, camRays, r, t.primary, t.offsets, surfaces, standing);
  size_t k = 0;  // the next hit's index in surfaces and standing
  size_t j = 0;  // the next ray's in primary
  for (int y = r.rows().begin(); y < r.rows().end(); ++y)
    for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
      const size_t i = img.index(x, y);
      if (batcher.full()) batcher.flush(ctx, img, counts.traced);
      batcher.beginPixel(i);
      bool first = true;
      for (uint32_t s = 0; s < spp; ++s, ++j) {
        const glm::vec3& dir = t.primary[j].ray.dir;
        const TraceHit th = t.primary[j].traceHit();
        if (!th.hit) {
          batcher.addMiss(ctx.lights.environmentRadiance(dir));
          continue;
        }
        if (stereo.reuse) prefetchPartnersAhead(*stereo.reuse, standing, k);
        const SurfaceHit& hit = surfaces[k];
        if (first) {
          img.depth[i] = cam.depthAt(th.t * glm::dot(dir, forward));
          img.normal[i] = hit.shadingNormal;
          first = false;
        }
        FirstBounce* record = stereo.record ? stereo.record->slot(i, s) : nullptr;
        SampleCounters counters{uint32_t(i),         eye, frame, s, 0, ctx.settings.seed, spp,
                                ctx.settings.sampler};
        const FirstBounce* partner =
            stereo.looksAcross() ? partnerOrOwnNumbers(stereo, hit, standing[k], s, counters)
                                 : nullptr;
        ++k;
        counts.reused += partner != nullptr;
        ++counts.paths;
        batcher.addHit(hit, dir, counters, record, partner,
                       tracesOwnShadowRay(ctx.settings, stereo, partner));
      }
      if (first) {  // every sample saw the environment: no hit, the far plane
        img.depth[i] = 0.0f;
        img.normal[i] = glm::vec3(0.0f);
      }
    }
  batcher.flush(ctx, img, counts.traced);
}

}  // namespace

EyeImage renderPathTraced(const TraceContext& ctx, const EyeCamera& cam, uint32_t eye,
                          uint32_t frame, EyeImage reuse, StereoRole stereo) {
  EyeImage img = std::move(reuse);
  sizeEyeImage(img, cam.width, cam.height);  // the tiles write every pixel's every plane
  if (stereo.record) stereo.record->reset(cam, uint32_t(ctx.settings.samplesPerPixel));
  std::atomic<uint64_t> rays{0}, rejected{0}, paths{0}, reused{0}, ownBounces{0};
  tbb::parallel_for(tbb::blocked_range2d<int>(0, cam.height, kTile, 0, cam.width, kTile),
                    [&](const tbb::blocked_range2d<int>& r) {
                      enableFlushToZero();
                      Counts counts;
                      traceTile(ctx, cam, eye, frame, stereo, r, img, counts);
                      rays += counts.traced.rays;
                      rejected += counts.traced.rejected;
                      ownBounces += counts.traced.ownBounces;
                      paths += counts.paths;
                      reused += counts.reused;
                    });
  img.rays = rays;
  img.paths = paths;
  img.reusedPaths = reused;
  img.reusedOwnBounces = ownBounces;
  img.rejectedSamples = rejected;
  traceCausticsInto(ctx, cam, frame, img, stereo.caustics);
  return img;
}

}  // namespace photovr
