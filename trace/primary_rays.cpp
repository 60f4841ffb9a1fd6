#include "trace/primary_rays.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <limits>

namespace photovr {

PrimaryRayStats timePrimaryRays(const Scene& scene, const EmbreeScene& embree,
                                const EyeCamera& cam) {
  std::atomic<uint64_t> hits{0};
  const CameraRays camRays(cam);
  const auto t0 = std::chrono::steady_clock::now();
  tbb::parallel_for(tbb::blocked_range2d<int>(0, cam.height, 16, 0, cam.width, 16),
                    [&](const tbb::blocked_range2d<int>& r) {
                      enableFlushToZero();
                      uint64_t local = 0;
                      for (int y = r.rows().begin(); y < r.rows().end(); ++y)
                        for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
                          const glm::vec3 dir = camRays.pixelRay(x, y);
                          const TraceHit h = embree.intersect(
                              cam.pose.position, dir, 0.0f, std::numeric_limits<float>::infinity(),
                              RayRole::Camera);
                          if (!h.hit) continue;
                          ++local;
                          // An out-of-line call (no LTO): the compiler cannot drop it.
                          surfaceAt(scene, h.instance, h.triangle, h.b1, h.b2, dir);
                        }
                      hits += local;
                    });
  PrimaryRayStats s;
  s.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  s.rays = uint64_t(cam.width) * cam.height;
  s.hits = hits;
  return s;
}

}  // namespace photovr
