// Stereo path reuse in the hybrid frame (trace/stereo_reuse.h): the samples of the eye
// traced second continue from its rasterized hits and reuse the first eye's paths (the eyes
// take turns); each eye's converged image must be the one its own paths give, within Monte
// Carlo error.
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "core/builtin_scenes.h"
#include "hybrid/hybrid_renderer.h"
#include "tests/gl/gl_test_util.h"
#include "tests/trace/image_statistics.h"

namespace photovr {
namespace {

// Each eye, reuse on against off, one test per built-in scene (so that they run side by
// side, and each fits its time under the sanitizers): region z-test of 128 frames at
// 32 x 36 (tests/trace/image_statistics.h: 17 tests at |z| < 4); with reuse on an eye reuses
// on every other frame. The paired form compares frame k on with frame k off, which draw the
// same numbers: the left eye's samples are the same bits when it traces first and correlate
// with its reused ones, so it sees what the unpaired test at this size cannot (the reused
// bounce term scaled by 1.05 fails it on every scene; scaled by 1.2, atrium's unpaired |z|
// was 2.6). The frames' G-buffers move with the jitter as a headset's do, so
// the partner test runs on rasterized hits.
class StereoReuseHybrid : public ::testing::TestWithParam<std::string> {};

TEST_P(StereoReuseHybrid, EachEyeConvergesToItsOwnPathsImage) {
  constexpr int kW = 32, kH = 36, kFrames = 128;
  testing::osmesaContext();
  const std::string& name = GetParam();
  const Scene scene = makeBuiltinScene(name);
  StereoRig rig;
  rig.head = poseOf(scene.cameras.at(0));
  HybridRenderer renderer(scene, kW, kH, TraceSettings{});
  std::array<std::array<std::vector<std::vector<glm::vec3>>, 2>, 2> frames;  // [on][eye]
  uint64_t reused = 0, paths = 0;
  for (int on = 0; on < 2; ++on) {
    TraceSettings s;
    s.stereoReuse = on == 1;
    renderer.setSettings(s);
    for (int k = 0; k < kFrames; ++k) {
      const glm::vec2 jitter = samplePosition(SamplerKind::Sobol, uint32_t(k));
      const std::array<EyeCamera, 2> eyes = {rig.eye(Eye::Left, kW, kH, jitter),
                                             rig.eye(Eye::Right, kW, kH, jitter)};
      FrameTimes t;
      auto img = renderer.render(eyes, 2, uint32_t(k), &t);
      if (on) reused += t.turnReusedPaths[1], paths += t.turnPaths[1];
      for (int e = 0; e < 2; ++e) frames[on][e].push_back(img[e].color);
      renderer.recycle(std::move(img));
    }
  }
  for (int e = 0; e < 2; ++e) {
    const double z =
        testing::maxRegionZ(testing::statisticsOf(frames[1][e], kW, kH),
                            testing::statisticsOf(frames[0][e], kW, kH), testing::kRegions);
    const double paired =
        testing::maxPairedRegionZ(frames[1][e], frames[0][e], kW, kH, testing::kRegions);
    EXPECT_LT(z, testing::kMaxZ) << name << " eye " << e;
    EXPECT_LT(paired, testing::kMaxZ) << name << " eye " << e << " (paired)";
    std::printf("  %-8s eye %d: max region |z| %.2f, paired %.2f\n", name.c_str(), e, z, paired);
  }
  // Most of the second eye sees what the first eye sees; the rest (the other eye's hidden
  // surfaces, the field's edge, glass) traces its own paths.
  EXPECT_GT(double(reused), 0.5 * double(paths)) << name;
  std::printf("  %-8s reused %.3f of the second eye's paths\n", name.c_str(),
              double(reused) / double(paths));
}

INSTANTIATE_TEST_SUITE_P(Scenes, StereoReuseHybrid, ::testing::ValuesIn(builtinSceneNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

}  // namespace
}  // namespace photovr
