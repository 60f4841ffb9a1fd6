// The bench's ray recorder and raw replay (bench/bench_trace.cpp): recording must see every
// ray the tracer casts and change nothing, and the replay must trace the same rays.
#include <tbb/global_control.h>

#include <gtest/gtest.h>

#include "core/builtin_scenes.h"
#include "trace/path_tracer.h"

namespace photovr {
namespace {

EyeImage render(const Scene& scene, const EmbreeScene& embree) {
  const LightSet lights(scene);
  TraceSettings settings;
  settings.samplesPerPixel = 2;
  const TraceContext ctx{scene, embree, lights, settings};
  StereoRig rig;
  rig.head = poseOf(scene.cameras.at(0));
  return renderPathTraced(ctx, rig.eye(Eye::Left, 16, 18, samplePosition(SamplerKind::Sobol, 0)), 0,
                          0);
}

TEST(RayRecorder, SeesEveryRayAndChangesNothing) {
  const Scene scene = makeBuiltinScene("cornell");
  EmbreeScene embree(scene);
  const EyeImage plain = render(scene, embree);
  RayRecorder recorder;
  embree.setRecorder(&recorder);
  const EyeImage recorded = render(scene, embree);
  embree.setRecorder(nullptr);
  const std::vector<RecordedRay> rays = recorder.take();
  EXPECT_EQ(recorded.color, plain.color);
  EXPECT_EQ(rays.size(), plain.rays);
  EXPECT_TRUE(recorder.take().empty());  // take() empties the buffers
  size_t occluded = 0;
  for (const RecordedRay& r : rays) occluded += r.kind == RecordedRay::Kind::Occluded;
  EXPECT_GT(occluded, 0u);  // cornell's area light: NEE casts shadow rays
  EXPECT_LT(occluded, rays.size());
}

// The rays a render of 'scene' casts.
std::vector<RecordedRay> recordedRays(const Scene& scene, EmbreeScene& embree) {
  RayRecorder recorder;
  embree.setRecorder(&recorder);
  render(scene, embree);
  embree.setRecorder(nullptr);
  return recorder.take();
}

TEST(RayRecorder, ReplayFindsWhatTheWrappersFind) {
  const Scene scene = makeBuiltinScene("atrium");  // alpha-mask and back-face filters
  EmbreeScene embree(scene);
  const std::vector<RecordedRay> rays = recordedRays(scene, embree);
  ReplayCounts expected;
  size_t cameraRays = 0;
  for (const RecordedRay& r : rays)
    if (r.kind != RecordedRay::Kind::Occluded) {
      const bool camera = r.kind == RecordedRay::Kind::Camera;
      cameraRays += camera;
      ++expected.intersectRays;
      expected.hits += embree
                           .intersect(r.origin, r.dir, r.tnear, r.tfar,
                                      camera ? RayRole::Camera : RayRole::Transport)
                           .hit;
    } else {
      ++expected.occludedRays;
      expected.blocked += embree.occluded(r.origin, r.dir, r.tnear, r.tfar);
    }
  const ReplayCounts got = embree.replay(rays.data(), rays.size());
  EXPECT_EQ(got.intersectRays, expected.intersectRays);
  EXPECT_EQ(got.hits, expected.hits);
  EXPECT_EQ(got.occludedRays, expected.occludedRays);
  EXPECT_EQ(got.blocked, expected.blocked);
  EXPECT_GT(got.hits, 0u);
  EXPECT_GT(cameraRays, 0u);  // pt's primary rays, replayed with the camera's culling
}

// A ReplayHitShader that returns 1 where the replay's hit is intersect()'s for that ray and
// the index names the ray, 0 elsewhere.
struct HitCheck {
  const EmbreeScene& embree;
  const std::vector<RecordedRay>& rays;

  static float shade(const void* user, const RecordedRay& ray, const ReplayHit& hit,
                     uint64_t index) {
    const auto& c = *static_cast<const HitCheck*>(user);
    const TraceHit th = c.embree.intersect(ray.origin, ray.dir, ray.tnear, ray.tfar);
    const bool same = th.hit && th.t == hit.t && th.instance == hit.instance &&
                      th.triangle == hit.triangle && th.b1 == hit.b1 && th.b2 == hit.b2;
    return same && &ray == &c.rays[index] && hit.ng != glm::vec3(0.0f) ? 1.0f : 0.0f;
  }
};

TEST(RayRecorder, TheReplaysHitShaderSeesEachHitOfItsRay) {
  const Scene scene = makeBuiltinScene("atrium");
  EmbreeScene embree(scene);
  const std::vector<RecordedRay> rays = recordedRays(scene, embree);
  const HitCheck check{embree, rays};
  tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
  const ReplayCounts got = embree.replayParallel(rays, HitCheck::shade, &check);
  EXPECT_GT(got.hits, 0u);
  EXPECT_EQ(got.shaded, double(got.hits));  // every hit, and only hits, matched (sums of 1s)
  EXPECT_EQ(got.intersectRays + got.occludedRays, rays.size());
}

TEST(RayRecorder, CollectsFromEveryThread) {
  const Scene scene = makeBuiltinScene("cornell");
  EmbreeScene embree(scene);
  RayRecorder recorder;
  embree.setRecorder(&recorder);
  tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
  const EyeImage img = render(scene, embree);
  EXPECT_EQ(recorder.take().size(), img.rays);
}

}  // namespace
}  // namespace photovr
