// Pure path tracing of an eye image: Embree primary rays through the same jittered pixel
// positions the rasterizer uses, then continuePath(), in parallel over tiles.
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <utility>

#include "trace/path_tracer.h"
#include "trace/pixel_estimate.h"

namespace photovr {
namespace {

constexpr int kTile = 16;  // 16 x 16 pixels: enough work per task, many tasks for balance

struct Counts {
  uint64_t rays = 0, rejected = 0;
};

// Sample s of frame f sits at the sampler's position for index f * spp + s
// (samplePosition): with one sample per frame that is the frame's jitter, where the
// G-buffer samples too; with more, each sample has its own place in the pixel, so one
// frame of N samples antialiases as N frames of one do. Depth and normal are the first
// hit's (the G-buffer keeps one surface per pixel too).
void tracePixel(const TraceContext& ctx, const EyeCamera& cam, uint32_t eye, uint32_t frame, int x,
                int y, EyeImage& img, Counts& counts) {
  const size_t i = img.index(x, y);
  const uint32_t spp = uint32_t(ctx.settings.samplesPerPixel);
  const glm::vec3 forward = cam.pose.orientation * glm::vec3(0, 0, -1);
  SampleCounters counters{uint32_t(i),         eye, frame, 0, 0, ctx.settings.seed, spp,
                          ctx.settings.sampler};
  PixelEstimate e;
  for (uint32_t s = 0; s < spp; ++s) {
    counters.sample = s;
    const glm::vec2 p = glm::vec2(x + 0.5f, y + 0.5f) +
                        samplePosition(ctx.settings.sampler, counters.sampleIndex());
    const glm::vec3 dir = cam.rayDirection(p.x, p.y);
    const TraceHit th =
        ctx.embree.intersect(cam.pose.position, dir, 0.0f, std::numeric_limits<float>::infinity());
    ++e.rays;
    if (!th.hit) {
      e.emitted += ctx.lights.environmentRadiance(dir);
      ++e.misses;
      continue;
    }
    const SurfaceHit hit = surfaceAt(ctx.scene, th.instance, th.triangle, th.b1, th.b2, dir);
    if (e.samples == 0) {
      img.depth[i] = cam.depthAt(th.t * glm::dot(dir, forward));
      img.normal[i] = hit.shadingNormal;
    }
    addPath(e, ctx, hit, dir, counters);
  }
  storePixel(img, i, e);
  counts.rays += e.rays;
  counts.rejected += e.rejected;
}

}  // namespace

EyeImage renderPathTraced(const TraceContext& ctx, const EyeCamera& cam, uint32_t eye,
                          uint32_t frame, EyeImage reuse) {
  EyeImage img = std::move(reuse);
  allocateEyeImage(img, cam.width, cam.height);
  std::atomic<uint64_t> rays{0}, rejected{0};
  tbb::parallel_for(tbb::blocked_range2d<int>(0, cam.height, kTile, 0, cam.width, kTile),
                    [&](const tbb::blocked_range2d<int>& r) {
                      enableFlushToZero();
                      Counts counts;
                      for (int y = r.rows().begin(); y < r.rows().end(); ++y)
                        for (int x = r.cols().begin(); x < r.cols().end(); ++x)
                          tracePixel(ctx, cam, eye, frame, x, y, img, counts);
                      rays += counts.rays;
                      rejected += counts.rejected;
                    });
  img.rays = rays;
  img.rejectedSamples = rejected;
  return img;
}

}  // namespace photovr
