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

// Sample s of frame f sits at the sampler's position for index f * spp + s
// (samplePosition): with one sample per frame that is the frame's jitter, where the
// G-buffer samples too; with more, each sample has its own place in the pixel, so one
// frame of N samples antialiases as N frames of one do. Depth and normal are the first
// hit's (the G-buffer keeps one surface per pixel too).
//
// A tile's primary rays go to Embree as one coherent batch, then its paths as batches of
// the wavefront tracer.
void traceTile(const TraceContext& ctx, const EyeCamera& cam, uint32_t eye, uint32_t frame,
               const StereoRole& stereo, const tbb::blocked_range2d<int>& r, EyeImage& img,
               Counts& counts) {
  const uint32_t spp = uint32_t(ctx.settings.samplesPerPixel);
  const glm::vec3 forward = cam.pose.orientation * glm::vec3(0, 0, -1);
  const CameraRays camRays(cam);
  thread_local std::vector<BatchRayHit> primary;
  thread_local std::vector<glm::vec2> positions;
  thread_local std::vector<glm::vec3> directions;
  thread_local PathBatcher batcher;
  // Sample s's offset in its pixel is the same in every pixel (samplePosition of frame * spp
  // + s): drawn once a tile, not per pixel (6 % of pt's reusing eye, perf).
  thread_local std::vector<glm::vec2> offsets;
  offsets.resize(spp);
  for (uint32_t s = 0; s < spp; ++s)
    offsets[s] = samplePosition(ctx.settings.sampler, frame * spp + s);
  positions.clear();
  for (int y = r.rows().begin(); y < r.rows().end(); ++y)
    for (int x = r.cols().begin(); x < r.cols().end(); ++x)
      for (uint32_t s = 0; s < spp; ++s)
        positions.push_back(glm::vec2(x + 0.5f, y + 0.5f) + offsets[s]);
  directions.resize(positions.size());
  sampleRays(camRays, positions, directions);
  primary.clear();
  // In place: a ray made on the stack and copied stalled on store forwarding.
  for (const glm::vec3& dir : directions)
    primary.emplace_back().ray.set(cam.pose.position, dir, 0.0f, kInfinity);
  ctx.embree.intersectBatch(primary.data(), primary.size(), ctx.settings.batchCall,
                            RayRole::Camera);
  counts.traced.rays += primary.size();
  // The hits' geometry in one vectorised pass, as the wavefront tracer's bounce hits.
  thread_local std::vector<HitRef> hits;
  thread_local std::vector<HitGeometry> geometry;
  hits.clear();
  for (const BatchRayHit& h : primary)
    if (h.geomID != ~0u) hits.push_back({h.traceHit().instance, h.primID, h.u, h.v});
  geometry.resize(hits.size());
  hitGeometries(ctx.scene, hits, geometry);
  // The tile's surfaces, built in place, and where the samples look across, each one's
  // standing pixel in the other eye's window, before any sample is added: a reusing eye's
  // partner records are then asked for ahead of their reads (prefetchPartnersAhead), as
  // the hybrid's tiles do (each had been a miss when findPartner read it).
  thread_local std::vector<SurfaceHit> surfaces;
  thread_local std::vector<StandingPixel> standing;
  growTo(surfaces, hits.size());
  growTo(standing, stereo.looksAcross() ? hits.size() : 0);
  for (size_t k = 0, j = 0; j < primary.size(); ++j) {
    if (primary[j].geomID == ~0u) continue;
    ::new (static_cast<void*>(&surfaces[k])) SurfaceHit(
        surfaceAt(ctx.scene, ctx.embree.materials(), hits[k], geometry[k], primary[j].ray.dir));
    ++k;
  }
  if (stereo.looksAcross())
    standingPixels(stereo, cam, camRays, r, primary, offsets,
                   std::span(surfaces).first(hits.size()), standing);
  size_t k = 0;  // the next hit's index in hits, geometry, surfaces and standing
  size_t j = 0;
  for (int y = r.rows().begin(); y < r.rows().end(); ++y)
    for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
      const size_t i = img.index(x, y);
      if (batcher.full()) batcher.flush(ctx, img, counts.traced);
      batcher.beginPixel(i);
      bool first = true;
      for (uint32_t s = 0; s < spp; ++s, ++j) {
        const glm::vec3& dir = primary[j].ray.dir;
        const TraceHit th = primary[j].traceHit();
        if (!th.hit) {
          batcher.addMiss(ctx.lights.environmentRadiance(dir));
          continue;
        }
        if (stereo.reuse)
          prefetchPartnersAhead(*stereo.reuse, std::span(standing).first(hits.size()), k);
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
  return img;
}

}  // namespace photovr
