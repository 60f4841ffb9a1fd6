// Issue 5's quality claim: a 1-spp hybrid frame denoised with 8 frames of history (static
// camera) against the raw 1-spp frame, both judged by relMSE against a converged
// reference, on each built-in scene.
//
// One 96x108 eye. The filter's footprints are in pixels (5 a-trous levels reach 32 pixels
// out), so at 48x54 the contact shadows of the spheres scene were 1-2 pixels tall inside a
// kernel wider than the image and the ratio measured under half of what it is at 96x108
// (3.5x vs 8.0x, before the firefly clamp); 96x108 is still 1/100 of a DK2 eye.
#include <gtest/gtest.h>

#include "core/builtin_scenes.h"
#include "core/error_metrics.h"
#include "gl/denoiser.h"
#include "hybrid/denoise_input.h"
#include "hybrid/hybrid_renderer.h"
#include "tests/gl/gl_test_util.h"
#include "tests/hybrid/reference_image.h"

namespace photovr {
namespace {

constexpr int kW = 96, kH = 108;

EyeCamera eyeOf(const Scene& s, uint32_t frame) {
  StereoRig rig;
  rig.head = poseOf(s.cameras.at(0));
  return rig.eye(Eye::Left, kW, kH, haltonJitter(frame));
}

// 'spp' samples over 32 jitter positions (the box-filtered pixel the resolve converges
// to; with 16 the spheres' ratio measured 8 % lower). The reference's own relMSE (~raw /
// spp) adds to the denoised image's measured error: the ratios below are pessimistic.
std::vector<glm::vec3> reference(const Scene& s, int spp) {
  return testing::referenceImage(s, eyeOf(s, 0), 32, spp / 32, 77);
}

struct Case {
  const char* scene;
  // cornell and atrium: 128 (their references cost 4x spheres' per sample; 1.5 / 128 =
  // 0.012 inflates the measured error ~1.6x, still far inside the 10x); spheres: 512,
  // whose denoised error is the closest to its guard (0.15 / 512 = 3e-4 against 0.011).
  int referenceSpp;
  // Required raw / denoised relMSE; the issue asks for 10x. Measured here (raw ->
  // denoised, tracer seeds 0 (the test's), 2, 3, 4): cornell 1.56-2.67 -> 0.0171-0.0180
  // (87-157x), atrium 1.56-1.85 -> 0.0297-0.0311 (50-61x), spheres 0.149-0.164 ->
  // 0.0101-0.0119 (15.2x, 13.7x, 15.3x, 12.5x). Before the resolve pass, the fwidth normal
  // test, the variance of the mean and the firefly clamp (at 48x54): cornell 7.9x, spheres
  // 1.2x, atrium 7.7x. spheres was at 8.6-10.2x until the colour history was taken from
  // the temporal output instead of the first a-trous iteration (gl/denoiser.h,
  // historyFromFirstIteration): three quarters of its denoised error was the same in every
  // seed, the filter re-applied through the history brightening the 1-2 pixel contact
  // shadows under the spheres, not noise. Over tracer seeds 0-25 spheres measures 10.8x
  // at seed 24 and 12.5-115x at the others; its raw relMSE is what varies (0.127 to 1.42:
  // fireflies), the denoised one stays at 0.0100-0.0154. Sampling the sun and the sky at
  // every vertex (instead of one of them, in proportion to power) lowered spheres' raw
  // relMSE more than its denoised one: 21x, 12x, 9.9x, 7.3x at the seeds above. All three
  // scenes are guarded at the target.
  double required;
};

class DenoiseQuality : public ::testing::TestWithParam<Case> {};

TEST_P(DenoiseQuality, EightFramesOfHistoryBeatTheRawFrame) {
  const Case c = GetParam();
  const Scene scene = makeBuiltinScene(c.scene);
  const std::vector<glm::vec3> ref = reference(scene, c.referenceSpp);
  testing::osmesaContext();
  HybridRenderer renderer(scene, kW, kH, true, TraceSettings{});
  gl::Denoiser denoiser(kW, kH);
  double raw = 0.0;
  std::vector<glm::vec3> denoised;
  for (int f = 0; f < 8; ++f) {
    const EyeCamera cam = eyeOf(scene, uint32_t(f));
    const EyeImage img = renderer.render({cam, cam}, 1, uint32_t(f), nullptr)[0];
    const DenoiseInput in = makeDenoiseInput(img);
    denoiser.run(renderer.gbuffer(), {in.eye, in.eye}, 1, gl::DenoiseMode::Full, f == 0);
    if (f == 7) {
      raw = relMse(img.color, ref);
      denoised = denoiser.readLinear(0);
    }
  }
  const double filtered = relMse(denoised, ref);
  RecordProperty("raw_relmse", std::to_string(raw));
  RecordProperty("denoised_relmse", std::to_string(filtered));
  EXPECT_LT(filtered * c.required, raw) << c.scene << ": raw " << raw << ", denoised " << filtered;
}

INSTANTIATE_TEST_SUITE_P(Scenes, DenoiseQuality,
                         ::testing::Values(Case{"cornell", 128, 10.0}, Case{"spheres", 512, 10.0},
                                           Case{"atrium", 128, 10.0}),
                         [](const auto& info) { return std::string(info.param.scene); });

}  // namespace
}  // namespace photovr
