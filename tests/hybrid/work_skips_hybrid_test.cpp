// The hybrid's skips (trace/work_skips.h): sky pixels the G-buffer saw no surface in are not
// traced, and a static scene's BVH is never refit. Turned off, each does its extra work and
// the image does not change.
#include <gtest/gtest.h>

#include "core/builtin_scenes.h"
#include "hybrid/hybrid_renderer.h"
#include "tests/gl/gl_test_util.h"
#include "tests/trace/image_statistics.h"

namespace photovr {
namespace {

constexpr int kWidth = 24, kHeight = 27;

struct HybridRun {
  std::vector<std::vector<glm::vec3>> colors;
  uint64_t rays = 0, background = 0;
  double refitMs = 0.0;
};

HybridRun render(const Scene& scene, const WorkSkips& skips, int frames) {
  testing::osmesaContext();
  TraceSettings settings;
  settings.skips = skips;
  HybridRenderer renderer(scene, kWidth, kHeight, settings);
  StereoRig rig;
  rig.head = poseOf(scene.cameras.at(0));
  HybridRun run;
  for (int f = 0; f < frames; ++f) {
    const EyeCamera cam =
        rig.eye(Eye::Left, kWidth, kHeight, samplePosition(SamplerKind::Sobol, uint32_t(f)));
    FrameTimes t;
    const EyeImage img = renderer.render({cam, cam}, 1, uint32_t(f), &t)[0];
    run.colors.push_back(img.color);
    run.rays += img.rays;
    run.refitMs += t.refitMs;
    for (float d : img.depth) run.background += d == 0.0f;  // reversed-Z: 0 = infinitely far
  }
  return run;
}

WorkSkips without(const std::string& name) {
  WorkSkips s;
  s.disable(name);
  return s;
}

TEST(HybridWorkSkips, SkyPixelsAreNotTraced) {
  const Scene scene = makeBuiltinScene("spheres");  // sky above the horizon
  const HybridRun on = render(scene, {}, 2), off = render(scene, without("sky-pixels"), 2);
  ASSERT_GT(on.background, 0u);
  // Off, each background pixel costs one primary ray and shows the same sky: the images are
  // identical (same seeds) and the ray count differs by exactly those rays.
  EXPECT_EQ(off.rays, on.rays + on.background);
  EXPECT_EQ(off.colors, on.colors);
}

TEST(HybridWorkSkips, StaticSceneIsNeverRefit) {
  const Scene scene = makeBuiltinScene("cornell");
  const int frames = 16;
  const HybridRun on = render(scene, {}, frames), off = render(scene, without("refit"), frames);
  EXPECT_EQ(on.refitMs, 0.0);
  EXPECT_GT(off.refitMs, 0.0);
  const auto a = testing::statisticsOf(on.colors, kWidth, kHeight);
  const auto b = testing::statisticsOf(off.colors, kWidth, kHeight);
  EXPECT_LT(testing::maxRegionZ(a, b, testing::kRegions), testing::kMaxZ);
}

}  // namespace
}  // namespace photovr
