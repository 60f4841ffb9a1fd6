// Pure path tracing of an eye image: Embree primary rays through the same jittered pixel
// positions the rasterizer uses, then continuePath(), in parallel over tiles.
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <atomic>

#include "trace/path_tracer.h"

namespace photovr {
namespace {

constexpr int kTile = 16;  // 16 x 16 pixels: enough work per task, many tasks for balance

struct PixelResult {
  glm::vec3 color{0.0f}, albedo{0.0f}, normal{0.0f};
  float depth = 0.0f;
  uint32_t rays = 0, rejected = 0;
};

PixelResult tracePixel(const TraceContext& ctx, const EyeCamera& cam, uint32_t eye, uint32_t frame,
                       int x, int y) {
  PixelResult px;
  const glm::vec3 origin = cam.pose.position;
  const glm::vec3 dir = cam.pixelRay(x, y);
  const TraceHit th =
      ctx.embree.intersect(origin, dir, 0.0f, std::numeric_limits<float>::infinity());
  px.rays = 1;
  const int spp = ctx.settings.samplesPerPixel;
  if (!th.hit) {
    px.color = ctx.lights.environmentRadiance(dir);
    return px;
  }
  const SurfaceHit hit = surfaceAt(ctx.scene, th.instance, th.triangle, th.b1, th.b2, dir);
  const glm::vec3 forward = cam.pose.orientation * glm::vec3(0, 0, -1);
  px.depth = cam.depthAt(th.t * glm::dot(dir, forward));
  px.normal = hit.shadingNormal;
  SampleCounters counters{uint32_t(y * cam.width + x), eye, frame, 0, 0, ctx.settings.seed};
  for (int s = 0; s < spp; ++s) {
    counters.sample = uint32_t(s);
    const PathResult r = continuePath(ctx, hit, -dir, counters);
    px.color += r.radiance;
    px.albedo += r.albedo;
    px.rays += r.rays;
    px.rejected += r.rejected;
  }
  px.color = px.color / float(spp) + hit.emission;
  px.albedo /= float(spp);
  return px;
}

}  // namespace

EyeImage renderPathTraced(const TraceContext& ctx, const EyeCamera& cam, uint32_t eye,
                          uint32_t frame) {
  EyeImage img;
  img.width = cam.width;
  img.height = cam.height;
  const size_t n = size_t(cam.width) * cam.height;
  img.color.assign(n, glm::vec3(0.0f));
  img.albedo.assign(n, glm::vec3(0.0f));
  img.normal.assign(n, glm::vec3(0.0f));
  img.depth.assign(n, 0.0f);
  img.samples.assign(n, 0);
  std::atomic<uint64_t> rays{0}, rejected{0};
  tbb::parallel_for(tbb::blocked_range2d<int>(0, cam.height, kTile, 0, cam.width, kTile),
                    [&](const tbb::blocked_range2d<int>& r) {
                      enableFlushToZero();
                      uint64_t tileRays = 0, tileRejected = 0;
                      for (int y = r.rows().begin(); y < r.rows().end(); ++y)
                        for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
                          const PixelResult px = tracePixel(ctx, cam, eye, frame, x, y);
                          const size_t i = img.index(x, y);
                          img.color[i] = px.color;
                          img.albedo[i] = px.albedo;
                          img.normal[i] = px.normal;
                          img.depth[i] = px.depth;
                          img.samples[i] = uint32_t(ctx.settings.samplesPerPixel);
                          tileRays += px.rays;
                          tileRejected += px.rejected;
                        }
                      rays += tileRays;
                      rejected += tileRejected;
                    });
  img.rays = rays;
  img.rejectedSamples = rejected;
  return img;
}

}  // namespace photovr
