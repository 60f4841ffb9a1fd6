// What feeds the denoiser's colour history (gl/denoiser.h, historyFromFirstIteration): a
// thin shadow on a plane, beside a sub-pixel edge that the per-frame jitter makes flicker
// between lit and shadowed (the spheres scene's contact shadows, one or two pixels tall).
// Fed back through the history, the first a-trous iteration's small leak across that edge
// compounds frame after frame; fed from the temporal output, it is paid once.
#include <gtest/gtest.h>

#include <random>

#include "gl/denoiser.h"
#include "tests/gl/denoiser_test_util.h"
#include "tests/gl/gl_test_util.h"

namespace photovr {
namespace {

using testing::SyntheticFrame;
using testing::SyntheticGBuffer;

constexpr int kW = 32, kH = 24;
constexpr int kEdgeRow = 11, kShadowRows[2] = {12, 13}, kFirstObjectRow = 14;
constexpr float kLit = 1.4f, kShadow = 0.2f, kObject = 0.6f;  // the spheres scene's floor

// Rows below the edge: the lit floor; the edge row: lit or shadowed, by a coin per frame
// (what the jitter does to a pixel the shadow's edge crosses); two shadowed rows; above,
// another object facing elsewhere. Each value with +-50 % uniform noise.
SyntheticFrame shadowFrame(std::mt19937& rng) {
  SyntheticFrame f(kW, kH);
  std::uniform_real_distribution<float> u(0.5f, 1.5f);
  std::bernoulli_distribution coin(0.5);
  for (int e = 0; e < 2; ++e)
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const bool object = y >= kFirstObjectRow;
        f.setSurface(e, x, y, object ? 1 : 0, 0, object ? 0.3f : 0.1f + 0.002f * float(y),
                     object ? glm::vec3(0, -0.6f, 0.8f) : glm::vec3(0, 0, 1));
        float v = y < kEdgeRow ? kLit : kShadow;
        if (y == kEdgeRow) v = coin(rng) ? kLit : kShadow;
        if (object) v = kObject;
        f.layer[e].diffuse[f.index(x, y)] = glm::vec3(v * u(rng));
      }
  return f;
}

// Mean over the shadow rows (all columns, both eyes) after 8 frames, relative to the truth.
double shadowBias(bool historyFromFirstIteration) {
  gl::DenoiseParams params;
  params.historyFromFirstIteration = historyFromFirstIteration;
  gl::Denoiser dn(kW, kH, params);
  SyntheticGBuffer gbuffer(kW, kH);
  std::mt19937 rng(11);
  for (int frame = 0; frame < 8; ++frame) {
    const SyntheticFrame f = shadowFrame(rng);
    gbuffer.upload(f);
    dn.run(gbuffer.geometry(), f.eyes(), 2, gl::DenoiseMode::Full, frame == 0);
  }
  double sum = 0.0;
  int n = 0;
  for (int e = 0; e < 2; ++e) {
    const std::vector<glm::vec3> img = dn.readLinear(e);
    for (int y : kShadowRows)
      for (int x = 0; x < kW; ++x, ++n) sum += img[size_t(y) * kW + x].g;
  }
  return sum / n / kShadow - 1.0;
}

TEST(DenoiseHistory, ThinShadowBesideAFlickeringEdgeKeepsItsDepth) {
  testing::osmesaContext();
  const double fromTemporal = shadowBias(false), fromFilter = shadowBias(true);
  RecordProperty("bias_history_from_temporal", std::to_string(fromTemporal));
  RecordProperty("bias_history_from_first_iteration", std::to_string(fromFilter));
  // Measured with noise seeds 11-14: +30-32 % from the temporal output (the leak of the 5
  // iterations, paid once), +59-62 % from the first iteration. The mean over 128 pixels
  // varies by ~1 % between noise seeds; the bounds sit between the two arrangements.
  EXPECT_LT(fromTemporal, 0.4);
  EXPECT_LT(fromTemporal, 0.7 * fromFilter);
}

}  // namespace
}  // namespace photovr
