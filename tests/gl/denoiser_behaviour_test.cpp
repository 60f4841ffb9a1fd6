// What the denoiser must do as a whole (issue 5): leave a clean image alone, leave no trail
// behind a moving object, and reduce noise over time as the moving average predicts.
#include <random>

#include <gtest/gtest.h>

#include "gl/denoiser.h"
#include "tests/gl/denoiser_test_util.h"
#include "tests/gl/gl_test_util.h"

namespace photovr {
namespace {

using testing::SyntheticFrame;
using testing::SyntheticGBuffer;
using testing::toHalf;

// A plane tilted in x and y (instance 0, one triangle) filling the frame.
SyntheticFrame planeFrame(int w, int h) {
  SyntheticFrame f(w, h);
  for (int e = 0; e < 2; ++e)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        f.setSurface(e, x, y, 0, 0, 0.1f + 0.002f * float(x) + 0.001f * float(y + e),
                     glm::vec3(0, 0, 1));
  return f;
}

constexpr gl::DenoiseMode kModes[] = {gl::DenoiseMode::Off, gl::DenoiseMode::Temporal,
                                      gl::DenoiseMode::Full};

TEST(DenoiserBehaviour, ConstantNoiseFreeImagePassesThroughUnchanged) {
  testing::osmesaContext();
  const int w = 16, h = 12;
  SyntheticFrame f = planeFrame(w, h);
  for (auto& l : f.layer) {
    std::fill(l.diffuse.begin(), l.diffuse.end(), toHalf(glm::vec3(0.5f, 0.25f, 3.0f)));
    std::fill(l.specular.begin(), l.specular.end(), toHalf(glm::vec3(0.1f, 0.2f, 0.3f)));
    std::fill(l.specularAlbedo.begin(), l.specularAlbedo.end(), glm::vec3(0.5f));
    std::fill(l.unfiltered.begin(), l.unfiltered.end(), glm::vec3(0.125f));
  }
  const glm::vec3 want = f.layer[0].diffuse[0] + 0.5f * f.layer[0].specular[0] + 0.125f;
  SyntheticGBuffer gbuffer(w, h);
  gbuffer.upload(f);
  for (gl::DenoiseMode mode : kModes) {
    gl::Denoiser dn(w, h);
    for (int frame = 0; frame < 3; ++frame)
      dn.run(gbuffer.geometry(), f.eyes(), 2, mode, frame == 0);
    for (int e = 0; e < 2; ++e) {
      const auto img = dn.readLinear(e);
      for (size_t i = 0; i < img.size(); ++i)
        for (int k = 0; k < 3; ++k)
          // Averages of equal values are that value to float rounding; storing the
          // composite as a half float rounds to nearest: 2^-11 relative.
          EXPECT_NEAR(img[i][k], want[k], want[k] / 2048.0f)
              << gl::denoiseModeName(mode) << " eye " << e << " pixel " << i << " channel " << k;
    }
  }
}

// A bright 3x3 object (instance 1, nearer) crosses a dark plane 3 pixels per frame and
// leaves the view; its motion vectors point back to where it was. Once it is gone, no
// pixel may remember it: the plane pixels it uncovered fail the instance test (§4.1), and
// in 'full' the resolve's per-pixel history is clamped into the 3x3 neighbourhood, which
// then holds only the plane.
TEST(DenoiserBehaviour, ObjectMovingOutOfViewLeavesNoTrail) {
  testing::osmesaContext();
  const int w = 24, h = 8, speed = 3;
  const glm::vec3 plane(0.1f), object(10.0f);
  for (gl::DenoiseMode mode : {gl::DenoiseMode::Temporal, gl::DenoiseMode::Full}) {
    gl::Denoiser dn(w, h);
    SyntheticGBuffer gbuffer(w, h);
    for (int t = 0; t < 9; ++t) {
      SyntheticFrame f = planeFrame(w, h);
      const int left = 8 + speed * t;  // out of view from t = 6
      for (int e = 0; e < 2; ++e)
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x) {
            const bool on = x >= left && x < left + 3 && y >= 2 && y < 5;
            if (on) f.setSurface(e, x, y, 1, 0, 0.5f, glm::vec3(0, 0, 1));
            f.layer[e].motion[f.index(x, y)] = on ? glm::vec2(-speed, 0) : glm::vec2(0);
            f.layer[e].diffuse[f.index(x, y)] = on ? object : plane;
          }
      gbuffer.upload(f);
      dn.run(gbuffer.geometry(), f.eyes(), 2, mode, t == 0);
      if (left < w) continue;
      for (int e = 0; e < 2; ++e) {
        const auto img = dn.readLinear(e);
        for (size_t i = 0; i < img.size(); ++i)
          ASSERT_NEAR(img[i].g, plane.g, 1e-3f)
              << gl::denoiseModeName(mode) << " frame " << t << " eye " << e << " pixel " << i;
      }
    }
  }
}

// A static noisy sequence: x_t = 1 + u_t, u uniform in [-0.5, 0.5) (variance 1/12), new
// per pixel and frame. With alpha_n = max(0.2, 1/n) (§4.1) the output after K frames is
// sum_k w_k x_k with known weights, so its variance is sigma^2 sum w_k^2 (-> alpha / (2 -
// alpha) = 1/9 of the input's). Measured over all pixels of both eyes.
TEST(DenoiserBehaviour, TemporalAccumulationReducesVarianceAsTheMovingAveragePredicts) {
  testing::osmesaContext();
  const int w = 32, h = 24, frames = 20;
  SyntheticFrame f = planeFrame(w, h);
  SyntheticGBuffer gbuffer(w, h);
  gbuffer.upload(f);
  gl::Denoiser dn(w, h);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  for (int t = 0; t < frames; ++t) {
    for (auto& l : f.layer)
      for (glm::vec3& c : l.diffuse) c = glm::vec3(1.0f + u(rng));
    dn.run(gbuffer.geometry(), f.eyes(), 2, gl::DenoiseMode::Temporal, t == 0);
  }
  std::vector<double> weights;  // weight of frame k in the output, newest last
  for (int n = 1; n <= frames; ++n) {
    const double a = std::max(0.2, 1.0 / n);
    for (double& x : weights) x *= 1.0 - a;
    weights.push_back(a);
  }
  double sumSq = 0.0;
  for (double x : weights) sumSq += x * x;
  const double predicted = sumSq / 12.0;

  double sum = 0.0, sq = 0.0;
  int n = 0;
  for (int e = 0; e < 2; ++e)
    for (const glm::vec3& c : dn.readLinear(e)) {
      sum += c.g;
      sq += double(c.g) * c.g;
      ++n;
    }
  const double mean = sum / n, variance = (sq - n * mean * mean) / (n - 1);
  // The sample variance of n Gaussian-like values has relative standard deviation
  // sqrt(2 / (n - 1)) = 3.6 % at n = 1536; 4 of those is the tolerance.
  const double tolerance = 4.0 * std::sqrt(2.0 / (n - 1));
  EXPECT_NEAR(variance / predicted, 1.0, tolerance) << variance << " vs " << predicted;
  EXPECT_NEAR(mean, 1.0, 4.0 * std::sqrt(predicted / n));
  EXPECT_LT(variance, (1.0 / 12.0) / 8.0);  // the EMA's 9x reduction, with margin
}

}  // namespace
}  // namespace photovr
