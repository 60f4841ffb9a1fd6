// Issue 5's quality claim, gated (issue 17): a 1-spp hybrid frame denoised with 8 frames of
// history (static camera), judged by relMSE against a converged reference, on each
// built-in scene, must stay within a fixed error budget.
//
// The gate is absolute, not a ratio to the raw frame. The denoised error is mostly bias
// (spheres: 3/4 of it the same in every seed), which does not fall with the input's
// variance, so "raw / denoised >= 10" fell when the tracer got better, and refused a
// lower-variance tracer change. A lower input variance can only lower the denoised error:
// less noise is left, and the a-trous luminance weight (phi = sigma_l sqrt(Var), SVGF eq. 5)
// narrows with it, which lowers the bias across edges too. The reference's own error (~raw
// / its spp) is part of the measured error, and falls with a better tracer as well.
//
// One 96x108 eye. The filter's footprints are in pixels (5 a-trous levels reach 32 pixels
// out), so at 48x54 the contact shadows of the spheres scene were 1-2 pixels tall inside a
// kernel wider than the image and the ratio measured under half of what it is at 96x108
// (3.5x vs 8.0x, before the firefly clamp); 96x108 is still 1/100 of a DK2 eye.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

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
  return rig.eye(Eye::Left, kW, kH, samplePosition(SamplerKind::Sobol, frame));
}

// 'spp' samples over 32 jitter positions (the box-filtered pixel the resolve converges
// to; with 16 the spheres' error measured 8 % higher).
std::vector<glm::vec3> reference(const Scene& s, int spp) {
  return testing::referenceImage(s, eyeOf(s, 0), 32, spp / 32, 77);
}

struct Case {
  const char* scene;
  // cornell and atrium: 96 (their references cost 4x spheres' per sample); spheres: 256.
  // The reference's own error (from the measured error's change with it: 128 -> 96, 512 ->
  // 256) is ~2/5 of cornell's measured error, ~1/3 of atrium's, ~1/20 of spheres'.
  int referenceSpp;
  // Budget for the mean denoised relMSE over the seeds: 1.5 x its mean over tracer seeds
  // 0-15 (cornell 0.0185, spheres 0.0113, atrium 0.0319). The 50 % is room for deliberate
  // trades between scenes (gl/denoiser.h records changes of up to +50 % on one scene, e.g.
  // historyFromFirstIteration on spheres); the seeds' own spread is 2 % per seed (cornell),
  // 2.3 % (atrium), 12 % (spheres, one seed of 16 at +39 %).
  double budget;
  // Whether a zero variance guide shows in this scene's error (see below): cornell and
  // atrium, not spheres.
  bool showsZeroVariance;
};

// The a-trous luminance weight is exp(-|l_p - l_q| / phi), phi = sigma_l sqrt(Var) + 1e-10:
// with the variance guide at 0 every tap of another luminance weighs 0 and the filter stops
// filtering (what is left is the temporal average, the firefly clamp and the resolve).
// sigma_l = 0 gives that same phi for any variance: the stand-in for a zero variance guide.
// Over seeds 0-15 it measures cornell 0.051-0.076 and atrium 0.132-0.145 (1.8x and 2.8x
// their budgets), spheres 0.0118-0.0139 against 0.0103-0.0157 denoised: there the temporal
// passes do most of the work. The old gate (raw / denoised >= 10, one seed) passed it on
// every scene: raw / that measures 20-52x, 11-105x, 11-14x.
gl::DenoiseParams zeroVarianceGuide() {
  gl::DenoiseParams p;
  p.sigmaLuminance = 0.0f;
  p.sigmaLuminanceSpecular = 0.0f;
  return p;
}

struct SequenceErrors {
  double raw = 0.0;              // the last raw frame's relMSE
  std::vector<double> denoised;  // per denoiser, after the 8th frame
};

// 8 frames from a fresh history under tracer seed 'seed', each denoiser fed the same frames.
SequenceErrors denoiseSequence(const Scene& scene, HybridRenderer& renderer,
                               const std::vector<gl::Denoiser*>& denoisers,
                               const std::vector<glm::vec3>& ref, uint32_t seed) {
  renderer.setSeed(seed);
  SequenceErrors e;
  for (int f = 0; f < 8; ++f) {
    const EyeCamera cam = eyeOf(scene, uint32_t(f));
    const EyeImage img = renderer.render({cam, cam}, 1, uint32_t(f), nullptr)[0];
    const DenoiseInput in = makeDenoiseInput(img);
    for (gl::Denoiser* d : denoisers)
      d->run(renderer.gbuffer(), {in.eye, in.eye}, 1, gl::DenoiseMode::Full, f == 0);
    if (f == 7) e.raw = relMse(img.color, ref);
  }
  for (gl::Denoiser* d : denoisers) e.denoised.push_back(relMse(d->readLinear(0), ref));
  return e;
}

struct SeedSpread {
  double mean = 0.0, standardError = 0.0;
};

SeedSpread spreadOf(const std::vector<double>& x) {
  SeedSpread s;
  for (double v : x) s.mean += v / double(x.size());
  double ss = 0.0;
  for (double v : x) ss += (v - s.mean) * (v - s.mean);
  s.standardError = std::sqrt(ss / double(x.size() - 1) / double(x.size()));
  return s;
}

std::string listed(const std::vector<double>& x) {
  std::string out;
  for (double v : x) out += (out.empty() ? "" : " ") + std::to_string(v);
  return out;
}

// Three tracer seeds, each an independent 8-frame sequence.
constexpr uint32_t kSeeds = 3;

struct SeedRuns {
  std::vector<double> raw, denoised;
  double zeroVarianceGuide = 0.0;  // seed 0, where the scene shows it
};

SeedRuns runSeeds(const Case& c, const Scene& scene, const std::vector<glm::vec3>& ref) {
  testing::osmesaContext();
  HybridRenderer renderer(scene, kW, kH, TraceSettings{});
  gl::Denoiser denoiser(kW, kH), blind(kW, kH, zeroVarianceGuide());
  SeedRuns runs;
  for (uint32_t seed = 0; seed < kSeeds; ++seed) {
    std::vector<gl::Denoiser*> run{&denoiser};
    // One seed suffices: blind, every seed of 0-15 measured at least 1.8x the budget.
    if (seed == 0 && c.showsZeroVariance) run.push_back(&blind);
    const SequenceErrors e = denoiseSequence(scene, renderer, run, ref, seed);
    runs.raw.push_back(e.raw);
    runs.denoised.push_back(e.denoised[0]);
    if (run.size() > 1) runs.zeroVarianceGuide = e.denoised[1];
  }
  return runs;
}

class DenoiseQuality : public ::testing::TestWithParam<Case> {};

TEST_P(DenoiseQuality, EightFramesOfHistoryStayWithinTheErrorBudget) {
  const Case c = GetParam();
  const Scene scene = makeBuiltinScene(c.scene);
  const SeedRuns runs = runSeeds(c, scene, reference(scene, c.referenceSpp));
  const SeedSpread s = spreadOf(runs.denoised);
  RecordProperty("raw_relmse", listed(runs.raw));
  RecordProperty("denoised_relmse", listed(runs.denoised));
  RecordProperty("zero_variance_guide_relmse", std::to_string(runs.zeroVarianceGuide));
  // Fails only when the mean is above the budget by more than 3 standard errors of it (from
  // the seeds' spread), so that seeds scattered by a firefly do not fail a good denoiser;
  // at the spread of seeds 0-15 the mean of 3 seeds would have to rise 7 (spheres) to 48
  // (cornell) standard errors to fail.
  EXPECT_LE(s.mean - 3.0 * s.standardError, c.budget)
      << c.scene << ": denoised " << listed(runs.denoised) << " (mean " << s.mean << " +- "
      << s.standardError << "), raw " << listed(runs.raw);
  // The gate's power: a denoiser blind to the variance does not pass it.
  if (c.showsZeroVariance) {
    EXPECT_GT(runs.zeroVarianceGuide, c.budget) << c.scene;
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, DenoiseQuality,
                         ::testing::Values(Case{"cornell", 96, 0.0277, true},
                                           Case{"spheres", 256, 0.0170, false},
                                           Case{"atrium", 96, 0.0479, true}),
                         [](const auto& info) { return std::string(info.param.scene); });

}  // namespace
}  // namespace photovr
