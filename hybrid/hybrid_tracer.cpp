#include "hybrid/hybrid_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "core/stopwatch.h"
#include "hybrid/hit_rebuild.h"
#include "trace/path_batcher.h"

namespace photovr {
namespace {

constexpr size_t kGrain = 256;  // pixels per task
constexpr float kInfinity = std::numeric_limits<float>::infinity();

// The standing pixels (stereo_reuse.h) of pixels [begin, end) that hit a surface, in one
// pass before the tile's samples need them, each record asked for as it is found: the
// lookups' arithmetic overlaps from pixel to pixel, and the records have arrived by the
// time the samples read them.
void standingPixels(const StereoRole& stereo, const gl::GBufferImage& g, const CameraRays& rays,
                    const EyeCamera& cam, std::span<const RebuiltHit> hits, size_t begin,
                    size_t end, std::vector<StandingPixel>& out) {
  out.assign(end - begin, StandingPixel{});
  const EyeWindow& window = windowOf(stereo);
  for (size_t i = begin; i < end; ++i) {
    if (!g.record(i).hit()) continue;
    const int x = int(i % size_t(g.width)), y = int(i / size_t(g.width));
    StandingPixel& s = out[i - begin];
    s = standingPixelOf(window, hits[i].surface,
                        {cam.pose.position, rays.throughCentre(x, y), cam.jitter, 0});
    if (stereo.reuse) prefetchPartner(*stereo.reuse, s);
  }
}

}  // namespace

EyeImage traceFromGBuffer(const TraceContext& ctx, const gl::GBufferImage& g, const EyeCamera& cam,
                          uint32_t eye, uint32_t frame, const SampleMap& samples,
                          HybridEyeStats* stats, HybridEyeBuffers* reuse, StereoRole stereo) {
  HybridEyeBuffers local;
  HybridEyeBuffers& buffers = reuse ? *reuse : local;
  EyeImage& img = buffers.image;
  allocateEyeImage(img, g.width, g.height);  // zeroes it, in place when it has the size
  const size_t n = size_t(g.width) * g.height;
  std::vector<RebuiltHit>& hits = buffers.hits;
  hits.resize(n);  // every element is written below: no second pass over ~95 MB
  std::atomic<uint64_t> outside{0}, rays{0}, rejected{0}, traced{0}, skyHits{0}, paths{0},
      reused{0}, ownBounces{0};
  if (stereo.record) stereo.record->reset(cam, uint32_t(ctx.settings.samplesPerPixel));
  const glm::vec3 forward = cam.pose.orientation * glm::vec3(0, 0, -1);
  const CameraRays camRays(cam);
  const auto t0 = Clock::now();
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, n, kGrain), [&](const tbb::blocked_range<size_t>& r) {
        outside +=
            rebuildPrimaryHits(ctx.scene, g, camRays, cam.pose.position, r.begin(), r.end(), hits);
      });
  const auto t1 = Clock::now();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kGrain), [&](const tbb::blocked_range<size_t>&
                                                                      r) {
    enableFlushToZero();
    PathBatcher::Totals tile;
    uint64_t tileTraced = 0, tileSkyHits = 0, tilePaths = 0, tileReused = 0;
    thread_local PathBatcher batcher;
    thread_local std::vector<StandingPixel> standing;
    if (stereo.looksAcross())
      standingPixels(stereo, g, camRays, cam, hits, r.begin(), r.end(), standing);
    for (size_t i = r.begin(); i < r.end(); ++i) {
      const glm::vec3& dir = hits[i].direction;
      if (!g.record(i).hit()) {               // background: the environment, untraced
        if (!ctx.settings.skips.skyPixels) {  // ... unless that skip is off
          ++tile.rays;
          if (ctx.embree.intersect(cam.pose.position, dir, 0.0f, kInfinity, RayRole::Camera).hit)
            ++tileSkyHits;
        }
        img.color[i] = ctx.lights.environmentRadiance(dir);
        continue;
      }
      const uint32_t spp = samples.samplesAt(i, uint32_t(ctx.settings.samplesPerPixel));
      img.normal[i] = hits[i].surface.shadingNormal;
      img.depth[i] = cam.depthAt(hits[i].t * glm::dot(dir, forward));
      if (spp == 0) continue;
      if (batcher.full()) batcher.flush(ctx, img, tile);
      batcher.beginPixel(i);
      SampleCounters counters{uint32_t(i),         eye, frame, 0, 0, ctx.settings.seed, spp,
                              ctx.settings.sampler};
      const SurfaceHit& hit = hits[i].surface;
      for (uint32_t s = 0; s < spp; ++s) {
        counters.sample = s;
        FirstBounce* record = stereo.record ? stereo.record->slot(i, s) : nullptr;
        SampleCounters own = counters;
        const FirstBounce* partner =
            stereo.looksAcross() ? partnerOrOwnNumbers(stereo, hit, standing[i - r.begin()], s, own)
                                 : nullptr;
        tileReused += partner != nullptr;
        batcher.addHit(hit, dir, own, record, partner);
      }
      tilePaths += spp;
      ++tileTraced;
    }
    batcher.flush(ctx, img, tile);
    rays += tile.rays;
    rejected += tile.rejected;
    ownBounces += tile.ownBounces;
    traced += tileTraced;
    skyHits += tileSkyHits;
    paths += tilePaths;
    reused += tileReused;
  });
  img.rays = rays;
  img.paths = paths;
  img.reusedPaths = reused;
  img.reusedOwnBounces = ownBounces;
  img.rejectedSamples = rejected;
  if (stats) {
    stats->rebuildMs = std::chrono::duration<double, std::milli>(t1 - t0).count();
    stats->traceMs = msSince(t1);
    stats->outsideHits = outside;
    stats->tracedPixels = traced;
    stats->skyRayHits = skyHits;
  }
  return std::move(img);
}

}  // namespace photovr
