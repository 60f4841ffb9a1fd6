// Frames traced into an earlier frame's storage (HybridRenderer::recycle, renderPathTraced's
// 'reuse'; docs/ARCHITECTURE.md, "Memory reuse") are bit-identical to frames traced into
// fresh memory: nothing of the earlier frame survives, not even where a pixel is skipped.
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include <array>
#include <utility>
#include <vector>

#include "core/builtin_scenes.h"
#include "hybrid/hybrid_renderer.h"
#include "tests/gl/gl_test_util.h"
#include "trace/embree_scene.h"
#include "trace/lights.h"
#include "trace/path_tracer.h"

namespace photovr {
namespace {

constexpr int kW = 32, kH = 36;

// Every field, exactly: the same work on the same inputs must give the same bits.
void expectIdentical(const EyeImage& a, const EyeImage& b) {
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  EXPECT_EQ(a.color, b.color);
  EXPECT_EQ(a.albedo, b.albedo);
  EXPECT_EQ(a.normal, b.normal);
  EXPECT_EQ(a.depth, b.depth);
  EXPECT_EQ(a.samples, b.samples);
  EXPECT_EQ(a.diffuse, b.diffuse);
  EXPECT_EQ(a.specular, b.specular);
  EXPECT_EQ(a.diffuseAlbedo, b.diffuseAlbedo);
  EXPECT_EQ(a.specularAlbedo, b.specularAlbedo);
  EXPECT_EQ(a.guide, b.guide);
  EXPECT_EQ(a.rays, b.rays);
  EXPECT_EQ(a.rejectedSamples, b.rejectedSamples);
}

// The scene's camera, or one turned half-way round: a frame that saw other surfaces (and
// other sky pixels) leaves other values behind in the storage.
std::array<EyeCamera, 2> eyes(const Scene& s, uint32_t frame, bool turned) {
  StereoRig rig;
  rig.head = poseOf(s.cameras.at(0));
  if (turned)
    rig.head.orientation = rig.head.orientation * glm::angleAxis(3.0f, glm::vec3(0, 1, 0));
  const glm::vec2 jitter = samplePosition(SamplerKind::Sobol, frame);
  return {rig.eye(Eye::Left, kW, kH, jitter), rig.eye(Eye::Right, kW, kH, jitter)};
}

// Half the pixels untraced (0 samples), as the hidden-area mask leaves them: their outputs
// must read as untraced, not as the last frame's.
std::vector<uint16_t> checkerSpp() {
  std::vector<uint16_t> spp(size_t(kW) * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) spp[size_t(y) * kW + x] = uint16_t((x / 4 + y / 4) % 2 ? 2 : 0);
  return spp;
}

TEST(StorageReuse, HybridFrameIntoRecycledStorageMatchesFreshOne) {
  const Scene scene = makeBuiltinScene("atrium");
  testing::osmesaContext();
  const std::vector<uint16_t> spp = checkerSpp();
  const StereoSampleMaps maps = {SampleMap(spp), SampleMap(spp)};
  HybridRenderer fresh(scene, kW, kH, TraceSettings{});
  const auto expected = fresh.render(eyes(scene, 1, false), 2, 1, nullptr, maps);

  HybridRenderer reused(scene, kW, kH, TraceSettings{});
  reused.recycle(reused.render(eyes(scene, 0, true), 2, 0, nullptr));  // every pixel traced
  const auto got = reused.render(eyes(scene, 1, false), 2, 1, nullptr, maps);
  for (int e = 0; e < 2; ++e) expectIdentical(got[e], expected[e]);
}

// Spheres' sky: the background pixels (no hit, samples 0) must read as such, not as the
// surfaces the turned frame saw there.
TEST(StorageReuse, PathTracedFrameIntoReusedImageMatchesFreshOne) {
  const Scene scene = makeBuiltinScene("spheres");
  const EmbreeScene embree(scene);
  const LightSet lights(scene);
  const TraceContext ctx{scene, embree, lights, TraceSettings{}};
  const EyeCamera cam = eyes(scene, 1, true)[0];
  const EyeImage expected = renderPathTraced(ctx, cam, 0, 1);
  EyeImage old = renderPathTraced(ctx, eyes(scene, 0, false)[0], 0, 0);
  ASSERT_NE(old.color, expected.color);
  size_t backgroundUnderHits = 0;  // pixels the fresh frame's sky covers, where the old one hit
  for (size_t i = 0; i < expected.samples.size(); ++i)
    backgroundUnderHits += expected.samples[i] == 0 && old.samples[i] > 0;
  ASSERT_GT(backgroundUnderHits, 0u);
  expectIdentical(renderPathTraced(ctx, cam, 0, 1, std::move(old)), expected);
}

}  // namespace
}  // namespace photovr
