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
#include "trace/caustics.h"
#include "trace/path_batcher.h"
#include "trace/standing_lanes.h"

namespace photovr {
namespace {

constexpr size_t kGrain = 256;  // pixels per task
constexpr float kInfinity = std::numeric_limits<float>::infinity();

// The standing pixels (stereo_reuse.h) of pixels [begin, end) that hit a surface (hits[i -
// begin] pixel i's), in SIMD lanes (trace/standing_lanes.h) before the tile's samples need
// them.
void standingPixels(const StereoRole& stereo, const gl::GBufferImage& g, const CameraRays& rays,
                    const EyeCamera& cam, std::span<const RebuiltHit> hits, size_t begin,
                    size_t end, std::vector<StandingPixel>& out) {
  out.assign(end - begin, StandingPixel{});
  thread_local std::vector<StandingJob> jobs;
  jobs.clear();
  // Walked, not divided: pixel i's x and y from the previous pixel's.
  int x = int(begin % size_t(g.width)) - 1, y = int(begin / size_t(g.width));
  for (size_t i = begin; i < end; ++i) {
    if (++x == g.width) x = 0, ++y;
    if (!g.record(i).hit()) continue;
    StandingJob& job = jobs.emplace_back();
    job.hit = &hits[i - begin].surface;
    job.centreRay = rays.throughCentre(x, y);
    job.out = &out[i - begin];
  }
  standingPixelsOf(windowOf(stereo), cam.pose.position, cam.jitter, jobs);
}

}  // namespace

EyeImage traceFromGBuffer(const TraceContext& ctx, const gl::GBufferImage& g, const EyeCamera& cam,
                          uint32_t eye, uint32_t frame, const SampleMap& samples,
                          HybridEyeStats* stats, HybridEyeBuffers* reuse, StereoRole stereo) {
  HybridEyeBuffers local;
  HybridEyeBuffers& buffers = reuse ? *reuse : local;
  EyeImage& img = buffers.image;
  sizeEyeImage(img, g.width, g.height);  // in place when it has the size: the tiles write it all
  const size_t n = size_t(g.width) * g.height;
  std::atomic<uint64_t> outside{0}, rays{0}, rejected{0}, traced{0}, skyHits{0}, paths{0},
      reused{0}, ownBounces{0};
  std::atomic<int64_t> rebuildNs{0}, traceNs{0};  // summed over the tiles
  if (stereo.record) stereo.record->reset(cam, uint32_t(ctx.settings.samplesPerPixel));
  const glm::vec3 forward = cam.pose.orientation * glm::vec3(0, 0, -1);
  const CameraRays camRays(cam);
  const auto t0 = Clock::now();
  // Each tile's hits are rebuilt right before it is traced, into a buffer of its own: as
  // a pass of its own over the image, the rebuild wrote every pixel's RebuiltHit (168
  // bytes) to memory and the trace read it back, 174 MB an eye at 960 x 1080.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kGrain), [&](const tbb::blocked_range<size_t>&
                                                                      r) {
    const auto start = Clock::now();
    thread_local std::vector<RebuiltHit> tileHits;  // pixel i's at i - r.begin()
    tileHits.resize(r.size());
    outside += rebuildPrimaryHits(ctx.scene, ctx.embree.materials(), g, camRays, cam.pose.position,
                                  r.begin(), r.end(), tileHits);
    const auto rebuilt = Clock::now();
    const std::span<const RebuiltHit> hits(tileHits);
    enableFlushToZero();
    PathBatcher::Totals tile;
    uint64_t tileTraced = 0, tileSkyHits = 0, tilePaths = 0, tileReused = 0;
    thread_local PathBatcher batcher;
    thread_local std::vector<StandingPixel> standing;
    if (stereo.looksAcross())
      standingPixels(stereo, g, camRays, cam, hits, r.begin(), r.end(), standing);
    for (size_t i = r.begin(); i < r.end(); ++i) {
      if (stereo.reuse)
        prefetchPartnersAhead(*stereo.reuse, std::span(standing).first(r.size()), i - r.begin());
      const RebuiltHit& rebuiltHit = hits[i - r.begin()];
      const glm::vec3& dir = rebuiltHit.direction;
      if (!g.record(i).hit()) {               // background: the environment, untraced
        if (!ctx.settings.skips.skyPixels) {  // ... unless that skip is off
          ++tile.rays;
          if (ctx.embree.intersect(cam.pose.position, dir, 0.0f, kInfinity, RayRole::Camera).hit)
            ++tileSkyHits;
        }
        storeUntracedPixel(img, i, ctx.lights.environmentRadiance(dir));
        img.normal[i] = glm::vec3(0.0f);
        img.depth[i] = 0.0f;  // reversed-Z: the far plane
        continue;
      }
      const uint32_t spp = samples.samplesAt(i, uint32_t(ctx.settings.samplesPerPixel));
      img.normal[i] = rebuiltHit.surface.shadingNormal;
      img.depth[i] = cam.depthAt(rebuiltHit.t * glm::dot(dir, forward));
      if (spp == 0) {  // a pixel the sample map leaves untraced (the lens never shows it)
        storeUntracedPixel(img, i, glm::vec3(0.0f));
        continue;
      }
      if (batcher.full()) batcher.flush(ctx, img, tile);
      batcher.beginPixel(i);
      SampleCounters counters{uint32_t(i),         eye, frame, 0, 0, ctx.settings.seed, spp,
                              ctx.settings.sampler};
      const SurfaceHit& hit = rebuiltHit.surface;
      for (uint32_t s = 0; s < spp; ++s) {
        counters.sample = s;
        FirstBounce* record = stereo.record ? stereo.record->slot(i, s) : nullptr;
        SampleCounters own = counters;
        const FirstBounce* partner =
            stereo.looksAcross() ? partnerOrOwnNumbers(stereo, hit, standing[i - r.begin()], s, own)
                                 : nullptr;
        tileReused += partner != nullptr;
        batcher.addHit(hit, dir, own, record, partner,
                       tracesOwnShadowRay(ctx.settings, stereo, partner));
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
    rebuildNs += (rebuilt - start).count();
    traceNs += (Clock::now() - rebuilt).count();
  });
  img.rays = rays;
  img.paths = paths;
  img.reusedPaths = reused;
  img.reusedOwnBounces = ownBounces;
  img.rejectedSamples = rejected;
  if (stats) {
    // The pass's wall time, shared between the stages as the tiles' time was.
    const double total = msSince(t0), tiles = double(rebuildNs + traceNs);
    stats->rebuildMs = tiles > 0.0 ? total * double(rebuildNs) / tiles : 0.0;
    stats->traceMs = total - stats->rebuildMs;
    stats->outsideHits = outside;
    stats->tracedPixels = traced;
    stats->skyRayHits = skyHits;
  }
  // The light tracer's caustics (trace/caustics.h), part of the tracer's time.
  const auto causticsStart = Clock::now();
  traceCausticsInto(ctx, cam, frame, img, stereo.caustics);
  if (stats) stats->traceMs += msSince(causticsStart);
  return std::move(img);
}

}  // namespace photovr
