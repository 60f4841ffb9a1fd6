// Stereo path reuse (trace/stereo_reuse.h): the right eye's samples that take the left
// eye's paths beyond their first hit must give the image the right eye's own paths give, in
// expectation; where both eyes stand at one place, exactly the left eye's image.
#include "trace/stereo_reuse.h"

#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "core/builtin_scenes.h"
#include "tests/trace/image_statistics.h"
#include "trace/path_tracer.h"

namespace photovr {
namespace {

struct Fixture {
  Scene scene;
  EmbreeScene embree;
  LightSet lights;
  TraceContext ctx;
  StereoRig rig;
  explicit Fixture(const std::string& name)
      : scene(makeBuiltinScene(name)),
        embree(scene),
        lights(scene),
        ctx{scene, embree, lights, {}} {
    rig.head = poseOf(scene.cameras.at(0));
  }
  std::array<EyeCamera, 2> eyes(int w, int h, uint32_t frame) const {
    const glm::vec2 jitter = samplePosition(SamplerKind::Sobol, frame);
    return {rig.eye(Eye::Left, w, h, jitter), rig.eye(Eye::Right, w, h, jitter)};
  }
};

// Both eyes of one pt frame; 'reuse': the right eye reuses the left's paths. 'rightKey':
// the eye index the right eye's own paths draw their numbers for (1; 0: the left's).
std::array<EyeImage, 2> stereoFrame(const TraceContext& ctx, const std::array<EyeCamera, 2>& eyes,
                                    uint32_t frame, bool reuse, StereoPaths& paths,
                                    uint32_t rightKey = 1) {
  std::array<EyeImage, 2> out;
  for (int e = 0; e < 2; ++e)
    out[e] = renderPathTraced(ctx, eyes[e], e == 0 ? 0 : rightKey, frame, {},
                              stereoRoleOf(reuse, e, 2, paths));
  return out;
}

// With both eyes one camera every right sample finds its own primary hit in the
// left eye: same vertex, same direction (Jacobian 1), same MIS weights, same numbers. The
// reused right image must then be the left's to float rounding, which checks the recorded
// radiance beyond x1, the re-weighted emission and the shared light samples term by term
// (the right eye's own paths, at smooth vertices, draw the left's numbers here too).
TEST(StereoReuse, EyesAtOnePlaceGiveTheLeftImage) {
  for (const std::string& name : builtinSceneNames()) {
    Fixture f(name);
    f.ctx.settings.samplesPerPixel = 2;
    StereoPaths paths;
    auto eyes = f.eyes(24, 27, 3);
    eyes[1] = eyes[0];
    const auto img = stereoFrame(f.ctx, eyes, 3, true, paths, 0);
    ASSERT_GT(img[1].reusedPaths, 0u) << name;
    size_t compared = 0;
    for (size_t i = 0; i < img[0].color.size(); ++i) {
      // 1e-4 relative + 1e-6: a handful of float roundings in the reconnection (the
      // direction renormalised, the radiance divided and re-multiplied by the throughput).
      const glm::vec3 a = img[0].color[i], b = img[1].color[i];
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(a[k], b[k], 1e-4f * a[k] + 1e-6f) << name << " pixel " << i;
      ++compared;
    }
    EXPECT_EQ(compared, img[0].color.size());
  }
}

// Right eye, reuse on against off: the same expected image region by region within Monte
// Carlo error on every built-in scene (spheres has the mirror and the glossy sweep: their
// right samples trace their own paths, the rough ones reuse). This bounds the shift's two
// approximations (radiance at x2 towards x1R taken as towards x1L, x1R -> x2 visibility as
// x1L's) at the resolution of the test: 6 sigma of 128 frames at 32 x 36.
TEST(StereoReuse, RightEyeConvergesToItsOwnPathsImage) {
  constexpr int kW = 32, kH = 36, kFrames = 128;
  for (const std::string& name : builtinSceneNames()) {
    Fixture f(name);
    std::array<std::vector<std::vector<glm::vec3>>, 2> right;
    StereoPaths paths;
    uint64_t reused = 0, total = 0;
    for (int on = 0; on < 2; ++on)
      for (int k = 0; k < kFrames; ++k) {
        const auto eyes = f.eyes(kW, kH, uint32_t(k));
        auto img = stereoFrame(f.ctx, eyes, uint32_t(k), on == 1, paths);
        if (on) reused += img[1].reusedPaths, total += img[1].paths;
        right[on].push_back(std::move(img[1].color));
      }
    const auto off = testing::statisticsOf(right[0], kW, kH);
    const auto onStats = testing::statisticsOf(right[1], kW, kH);
    const double z = testing::maxRegionZ(onStats, off, testing::kRegions);
    EXPECT_LT(z, testing::kMaxZ) << name;
    EXPECT_GT(reused, 0u) << name;
    std::printf("  %-8s reused %.3f of the right eye's paths, max region |z| %.2f\n", name.c_str(),
                double(reused) / double(total), z);
  }
}

}  // namespace
}  // namespace photovr
