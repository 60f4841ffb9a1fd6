// The batched tracer against the scalar one it replaced: the same paths, the same numbers.
// Both run trace/path_stages.h's steps, so every difference would come from the batching
// itself (a path reading another's state, a ray answered for the wrong path, a pixel's
// samples summed in another order): the comparison is exact, not statistical.
#include "trace/wavefront.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "core/builtin_scenes.h"
#include "trace/path_batcher.h"
#include "trace/pixel_estimate.h"

namespace photovr {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

struct Fixture {
  Scene scene;
  EmbreeScene embree;
  LightSet lights;
  TraceContext ctx;
  EyeCamera cam;
  Fixture(const std::string& name, int spp, BatchCall call)
      : scene(makeBuiltinScene(name)),
        embree(scene),
        lights(scene),
        ctx{scene, embree, lights, {}} {
    ctx.settings.samplesPerPixel = spp;
    ctx.settings.batchCall = call;
    StereoRig rig;
    rig.head = poseOf(scene.cameras.at(0));
    cam = rig.eye(Eye::Left, 20, 24, samplePosition(SamplerKind::Sobol, 0));
  }
};

// What renderPathTraced computed before it was batched: each sample's primary ray, its hit
// and continuePath, one after another.
EyeImage scalarReference(const TraceContext& ctx, const EyeCamera& cam, uint32_t frame) {
  EyeImage img;
  allocateEyeImage(img, cam.width, cam.height);
  const uint32_t spp = uint32_t(ctx.settings.samplesPerPixel);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const size_t i = img.index(x, y);
      SampleCounters c{uint32_t(i), 0, frame, 0, 0, ctx.settings.seed, spp, ctx.settings.sampler};
      PixelEstimate e;
      for (uint32_t s = 0; s < spp; ++s) {
        c.sample = s;
        const glm::vec2 p =
            glm::vec2(x + 0.5f, y + 0.5f) + samplePosition(ctx.settings.sampler, c.sampleIndex());
        const glm::vec3 dir = cam.rayDirection(p.x, p.y);
        const TraceHit th =
            ctx.embree.intersect(cam.pose.position, dir, 0.0f, kInfinity, RayRole::Camera);
        if (!th.hit) {
          addMissedRay(e, ctx.lights.environmentRadiance(dir));
          continue;
        }
        const SurfaceHit hit = surfaceAt(ctx.scene, th.instance, th.triangle, th.b1, th.b2, dir);
        addPath(e, hit.emission, continuePath(ctx, hit, -dir, c));
      }
      storePixel(img, i, e);
      img.rays += e.rays + spp;
    }
  return img;
}

template <typename T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

void expectSameImage(const EyeImage& a, const EyeImage& b, const std::string& what) {
  EXPECT_TRUE(sameBits(a.color, b.color)) << what;
  EXPECT_TRUE(sameBits(a.diffuse, b.diffuse)) << what;
  EXPECT_TRUE(sameBits(a.specular, b.specular)) << what;
  EXPECT_TRUE(sameBits(a.albedo, b.albedo)) << what;
  EXPECT_EQ(a.samples, b.samples) << what;
  EXPECT_EQ(a.rays, b.rays) << what;
}

// 3 spp: a 16 x 16 tile's 768 paths make one batch, and the 20 x 24 image has partial tiles.
TEST(Wavefront, PathTracedImagesEqualTheScalarTracersBitForBitOnEveryBuiltinScene) {
  for (const std::string& name : builtinSceneNames())
    for (BatchCall call : {BatchCall::Stream, BatchCall::Single}) {
      const Fixture f(name, 3, call);
      const std::string what = name + (call == BatchCall::Stream ? " stream" : " single");
      expectSameImage(renderPathTraced(f.ctx, f.cam, 0, 2), scalarReference(f.ctx, f.cam, 2), what);
    }
}

// 40 spp: a tile's 10240 paths are flushed in batches of kBatchPaths, between pixels.
TEST(Wavefront, ManySamplesPerPixelSpanSeveralBatchesAndStillEqualTheScalarTracer) {
  const Fixture f("cornell", 40, BatchCall::Stream);
  expectSameImage(renderPathTraced(f.ctx, f.cam, 0, 0), scalarReference(f.ctx, f.cam, 0),
                  "cornell 40 spp");
}

// A path's result does not depend on the paths batched with it.
TEST(Wavefront, APathsResultDoesNotDependOnItsBatch) {
  const Fixture f("atrium", 1, BatchCall::Stream);
  std::vector<PathStart> starts;
  for (int y = 0; y < f.cam.height; ++y)
    for (int x = 0; x < f.cam.width; ++x) {
      const glm::vec3 dir = f.cam.pixelRay(x, y);
      const TraceHit th =
          f.embree.intersect(f.cam.pose.position, dir, 0.0f, kInfinity, RayRole::Camera);
      if (!th.hit) continue;
      starts.push_back(
          {surfaceAt(f.scene, th.instance, th.triangle, th.b1, th.b2, dir), -dir,
           SampleCounters{uint32_t(starts.size()), 0, 0, 0, 0, 7, 1, SamplerKind::Sobol}});
    }
  ASSERT_GT(starts.size(), 100u);
  std::vector<PathResult> together(starts.size());
  WavefrontScratch scratch;
  continuePaths(f.ctx, starts, together, scratch);
  for (size_t k = 0; k < starts.size(); ++k) {
    PathResult alone;
    continuePaths(f.ctx, std::span(&starts[k], 1), std::span(&alone, 1), scratch);
    ASSERT_EQ(std::memcmp(&alone.radiance, &together[k].radiance, sizeof(glm::vec3)), 0) << k;
    ASSERT_EQ(alone.rays, together[k].rays) << k;
  }
}

// The batch calls answer each ray as the single calls do: 500 rays from the camera and 500
// between random points inside the scene's bounds, through streams and one by one.
TEST(Wavefront, BatchCallsAnswerEachRayAsSingleCallsDo) {
  const Fixture f("spheres", 1, BatchCall::Stream);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<BatchRay> rays;
  for (int k = 0; k < 500; ++k)
    rays.push_back(
        BatchRay::make(f.cam.pose.position, f.cam.pixelRay(k % 20, k / 20 % 24), 0.0f, kInfinity));
  for (int k = 0; k < 500; ++k) {
    const glm::vec3 a(4 * u(rng), 2 + 2 * u(rng), 4 * u(rng)),
        b(4 * u(rng), 2 + 2 * u(rng), 4 * u(rng));
    rays.push_back(BatchRay::make(a, glm::normalize(b - a), 0.0f, glm::length(b - a)));
  }
  for (BatchCall call : {BatchCall::Stream, BatchCall::Single}) {
    std::vector<BatchRayHit> hits;
    for (const BatchRay& r : rays) hits.push_back({r});
    std::vector<BatchRay> shadows = rays;
    f.embree.intersectBatch(hits.data(), hits.size(), call);
    f.embree.occludedBatch(shadows.data(), shadows.size(), call);
    size_t blocked = 0, found = 0;
    for (size_t k = 0; k < rays.size(); ++k) {
      const BatchRay& r = rays[k];
      const TraceHit one = f.embree.intersect(r.origin, r.dir, r.tnear, r.tfar);
      const TraceHit many = hits[k].traceHit();
      ASSERT_EQ(one.hit, many.hit) << k;
      found += one.hit;
      if (one.hit) {
        EXPECT_EQ(one.t, many.t) << k;
        EXPECT_EQ(one.instance, many.instance) << k;
        EXPECT_EQ(one.triangle, many.triangle) << k;
        EXPECT_EQ(one.b1, many.b1) << k;
        EXPECT_EQ(one.b2, many.b2) << k;
      }
      const bool single = f.embree.occluded(r.origin, r.dir, r.tnear, r.tfar);
      EXPECT_EQ(single, shadows[k].blocked()) << k;
      blocked += single;
    }
    // Both answers occur, or the comparison proves little.
    EXPECT_GT(found, 100u);
    EXPECT_LT(found, rays.size());
    EXPECT_GT(blocked, 10u);
  }
}

}  // namespace
}  // namespace photovr
