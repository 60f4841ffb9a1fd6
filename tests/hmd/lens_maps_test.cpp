// Hidden-area mask, distortion-pass footprint, lens density and spp maps.
#include "hmd/lens_maps.h"

#include <gtest/gtest.h>

namespace photovr::hmd {
namespace {

// A quarter-resolution DK2 eye buffer (the thesis's 1/4 of 1182x1461 is ~296x365) keeps
// these maps fast under ASan; the geometry does not depend on resolution.
EyeBufferSpec smallSpec(Eye eye = Eye::Left) {
  const FovTangents fov = FovTangents::dk2LeftEye();
  return {eye, eye == Eye::Left ? fov : fov.mirrored(), 296, 365};
}

size_t at(const EyeBufferSpec& s, int x, int y) {
  return size_t(y) * s.width + x;
}

TEST(HiddenArea, CornersHiddenCentreVisible) {
  const LensModel m;
  for (Eye eye : {Eye::Left, Eye::Right}) {
    const EyeBufferSpec s = smallSpec(eye);
    const auto hidden = hiddenAreaMask(m, s);
    for (auto [x, y] :
         {std::pair{0, 0}, {s.width - 1, 0}, {0, s.height - 1}, {s.width - 1, s.height - 1}})
      EXPECT_EQ(hidden[at(s, x, y)], 1) << x << "," << y;
    // The lens axis and a generous disc around it are visible.
    const glm::dvec2 c = tanToEyeBuffer(s.fov, s.width, s.height, {0, 0});
    for (int dy = -60; dy <= 60; dy += 10)
      for (int dx = -60; dx <= 60; dx += 10)
        EXPECT_EQ(hidden[at(s, int(c.x) + dx, int(c.y) + dy)], 0);
    size_t n = 0;
    for (uint8_t h : hidden) n += h;
    // Tan-space field: a disc inside the screen's image, radius MaxR through the spline,
    // 1.38 for green and 1.38 * (1 + CA2 + CA3) = 1.43 for blue, which reaches farthest.
    // The 2.15 x 2.66 buffer loses four corner caps beyond 1.43: 6.1 % of its area by
    // numerical integration; the 1-pixel rim kept for bilinear taps brings it to ~5.7 %.
    const double fraction = double(n) / hidden.size();
    EXPECT_GT(fraction, 0.04);
    EXPECT_LT(fraction, 0.08);
  }
}

TEST(HiddenArea, NeverHidesATexelTheDistortionPassReads) {
  const LensModel m;
  const EyeBufferSpec s = smallSpec();
  const auto hidden = hiddenAreaMask(m, s);
  const auto read = distortionFootprint(m, s);
  size_t conflicts = 0, unreadVisible = 0, hiddenCount = 0;
  for (size_t i = 0; i < hidden.size(); ++i) {
    conflicts += hidden[i] && read[i];
    unreadVisible += !hidden[i] && !read[i];
    hiddenCount += hidden[i];
  }
  EXPECT_EQ(conflicts, 0u);
  // The mask is tight: visible-but-unread texels are only its one-pixel rim (dilation),
  // a thin ring well under the hidden area itself.
  EXPECT_LT(unreadVisible, hiddenCount / 5);
}

TEST(LensDensity, HighestAtTheLensCentreAndFallingOutward) {
  const LensModel m;
  const EyeBufferSpec s = smallSpec();
  const auto density = lensDensity(m, s);
  const glm::dvec2 c = tanToEyeBuffer(s.fov, s.width, s.height, {0, 0});
  const int cx = int(c.x), cy = int(c.y);
  const float centre = density[at(s, cx, cy)];
  EXPECT_NEAR(centre, *std::max_element(density.begin(), density.end()), 1e-3f * centre);
  // Along a ray from the centre the lens spreads display pixels ever thinner.
  float previous = centre;
  for (int x = cx + 10; x < s.width - 2; x += 10) {
    const float d = density[at(s, x, cy)];
    EXPECT_LT(d, previous) << x;
    previous = d;
  }
  // At the DK2's recommended 1182-px width the centre is 1:1 (549.6 px/tan both ways,
  // dk2.md §5); at a quarter of it, each buffer pixel feeds ~16 display pixels.
  const double expected = (549.6 * 549.6) / (296.0 / 2.151 * 365.0 / 2.6586);
  EXPECT_NEAR(centre, expected, 0.01 * expected);
}

TEST(LensMatchedSpp, ZeroWhereHiddenMaxAtCentre) {
  const LensModel m;
  const EyeBufferSpec s = smallSpec();
  const auto spp = lensMatchedSpp(m, s, 8);
  const auto hidden = hiddenAreaMask(m, s);
  for (size_t i = 0; i < spp.size(); ++i) {
    ASSERT_EQ(spp[i] == 0, hidden[i] == 1) << i;
    ASSERT_LE(spp[i], 8);
  }
  const glm::dvec2 c = tanToEyeBuffer(s.fov, s.width, s.height, {0, 0});
  EXPECT_EQ(spp[at(s, int(c.x), int(c.y))], 8);
  EXPECT_LT(spp[at(s, 2, int(c.y))], 8);  // the outer edge needs fewer
}

TEST(ThesisZones, MatchesAlgorithm6ByHand) {
  const int w = 100, h = 100, maxSpp = 8;
  const auto spp = thesisZoneSpp(w, h, maxSpp);
  // Centre pixel (d = 0.71): 1 + ceil(0.125 * 0.986 * 7) + ceil((1 - tiny) * 7) = 1+1+7 -> 8.
  EXPECT_EQ(spp[50 * w + 50], 8);
  // (90, 50): d = 40.5 > m = 40, nd = 0.81: 1 + ceil(0.125 * 0.19 * 7) = 2.
  EXPECT_EQ(spp[50 * w + 90], 2);
  // (70, 50): d = 20.5, nd = 0.41: 1 + ceil(0.516) + ceil((1 - 0.2627) * 7 = 5.16) = 8.
  EXPECT_EQ(spp[50 * w + 70], 8);
  // (80, 50): d = 30.5, nd = 0.61: 1 + 1 + ceil((1 - 0.5814) * 7 = 2.93) = 5.
  EXPECT_EQ(spp[50 * w + 80], 5);
  EXPECT_EQ(spp[0], 1);  // corner: nd > 1, clamped to one sample
}

}  // namespace
}  // namespace photovr::hmd
