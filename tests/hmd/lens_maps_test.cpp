// Hidden-area mask, distortion-pass footprint, lens density and spp maps.
#include "hmd/lens_maps.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/quaternion.hpp>
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

// Eye-buffer texels the lens shows, over a grid of display pixels and all channels, after
// the head turned by R (pure rotation: no parallax): the direction shown at the new pose,
// R d, found in the buffer rendered at the old one. Counts taps outside the buffer and
// taps on hidden texels. Only display pixels whose direction lies in the lens's field
// (the DK2's FOV tangents) count: the pincushion lens also shows a sliver beyond the
// field's straight edges, which no buffer of that FOV holds even with the head still.
struct TurnFootprint {
  int outside = 0, hidden = 0, taps = 0;
};

TurnFootprint footprintAfterTurn(const LensModel& m, const EyeBufferSpec& s,
                                 const std::vector<uint8_t>& hidden, const glm::dquat& turn) {
  TurnFootprint f;
  const int dw = m.panel.eyeWidth(), dh = m.panel.eyeHeight();
  const FovTangents field =
      s.eye == Eye::Left ? FovTangents::dk2LeftEye() : FovTangents::dk2LeftEye().mirrored();
  for (int py = 0; py < dh; py += 6)
    for (int px = 0; px < dw; px += 6) {
      const glm::dvec2 screen((px + 0.5) * 2.0 / dw - 1.0, (py + 0.5) * 2.0 / dh - 1.0);
      if (!lensSees(m, s.eye, screen)) continue;
      for (Channel c : {Channel::Red, Channel::Green, Channel::Blue}) {
        const glm::dvec2 t = screenToTan(m, s.eye, screen, c);
        if (t.x < -field.left || t.x > field.right || t.y < -field.down || t.y > field.up) continue;
        const glm::dvec3 d = turn * glm::dvec3(t, -1.0);
        const glm::dvec2 p = tanToEyeBuffer(s.fov, s.width, s.height, glm::dvec2(d) / -d.z) - 0.5;
        const int x0 = int(std::floor(p.x)), y0 = int(std::floor(p.y));
        for (auto [x, y] : {std::pair{x0, y0}, {x0 + 1, y0}, {x0, y0 + 1}, {x0 + 1, y0 + 1}}) {
          ++f.taps;
          if (x < 0 || y < 0 || x >= s.width || y >= s.height)
            ++f.outside;
          else
            f.hidden += hidden[at(s, x, y)];
        }
      }
    }
  return f;
}

// Turns of exactly 'deg': about each axis both ways, and diagonals.
std::vector<glm::dquat> turnsOf(double deg) {
  std::vector<glm::dquat> turns;
  const double a = glm::radians(deg);
  for (glm::dvec3 axis : {glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 1),
                          glm::dvec3(1, 1, 0), glm::dvec3(1, -1, 0), glm::dvec3(1, 1, 1)})
    for (double sign : {1.0, -1.0}) turns.push_back(glm::angleAxis(sign * a, glm::normalize(axis)));
  return turns;
}

EyeBufferSpec overscanSpec(Eye eye, double deg) {
  const StereoLayout l = StereoLayout::dk2(296, 365, float(glm::radians(deg)));
  return EyeBufferSpec::of(l, eye);
}

TEST(Overscan, EveryTexelATurnWithinTheMarginShowsIsRenderedAndNotHidden) {
  const LensModel m;
  for (Eye eye : {Eye::Left, Eye::Right}) {
    const EyeBufferSpec s = overscanSpec(eye, 3.0);
    const auto hidden = hiddenAreaMask(m, s);
    // Up to just under the margin: a turn of exactly 3 deg puts the field's edge on the
    // buffer's edge, half a texel beyond its last texel centre, where bilinear taps fall out.
    for (double deg : {1.0, 2.95}) {
      const std::vector<glm::dquat> turns = turnsOf(deg);
      for (size_t i = 0; i < turns.size(); ++i) {
        const TurnFootprint f = footprintAfterTurn(m, s, hidden, turns[i]);
        EXPECT_GT(f.taps, 10000);
        EXPECT_EQ(f.outside, 0) << deg << " deg, turn " << i;
        EXPECT_EQ(f.hidden, 0) << deg << " deg, turn " << i;
      }
    }
  }
}

TEST(Overscan, WithoutItATurnLooksPastTheBufferAndIntoTheHiddenArea) {
  const LensModel m;
  const EyeBufferSpec s = smallSpec();
  const auto hidden = hiddenAreaMask(m, s);
  // The property above is not vacuous: the plain buffer fails it for a 3 deg yaw.
  const TurnFootprint f =
      footprintAfterTurn(m, s, hidden, glm::angleAxis(glm::radians(3.0), glm::dvec3(0, 1, 0)));
  EXPECT_GT(f.outside, 0);
  EXPECT_GT(f.hidden, 0);
}

TEST(Overscan, TracesOnlyARingAroundTheLensField) {
  const LensModel m;
  const EyeBufferSpec plain = smallSpec(), over = overscanSpec(Eye::Left, 3.0);
  const auto count = [](const std::vector<uint8_t>& hidden) {
    return double(std::count(hidden.begin(), hidden.end(), uint8_t(0)));
  };
  const double plainSeen = count(hiddenAreaMask(m, plain));
  const double overSeen = count(hiddenAreaMask(m, over));
  const auto hidden = hiddenAreaMask(m, over);
  // The overscanned buffer's far corners stay hidden: no turn within 3 deg reaches them.
  EXPECT_EQ(hidden[at(over, 0, 0)], 1);
  EXPECT_EQ(hidden[at(over, over.width - 1, over.height - 1)], 1);
  // More is traced, but less than the buffer grew by: 3 deg adds ~8 % a side, so ~35 %
  // to the buffer (1.16^2); the ring traced is what a turn can bring in.
  const double grown = double(over.width) * over.height / (double(plain.width) * plain.height);
  EXPECT_GT(overSeen, plainSeen);
  EXPECT_LT(overSeen / plainSeen, grown);
}

TEST(LensDensity, OverscanPixelsGetTheLowestDensityTheLensShows) {
  const LensModel m;
  const EyeBufferSpec s = overscanSpec(Eye::Left, 2.0);
  const auto density = lensDensity(m, s);
  const auto hidden = hiddenAreaMask(m, s);
  float lowest = std::numeric_limits<float>::max(), highest = 0.0f;
  for (size_t i = 0; i < density.size(); ++i) {
    EXPECT_TRUE(std::isfinite(density[i]));
    EXPECT_EQ(density[i] > 0.0f, hidden[i] == 0) << i;
    if (density[i] > 0.0f) lowest = std::min(lowest, density[i]);
    highest = std::max(highest, density[i]);
  }
  // A margin pixel 1 deg beyond the field's left edge, at the lens axis's height, is at the
  // minimum; one 2.5 deg beyond is past what a 2 deg turn brings in: hidden (the buffer
  // reaches ~2.7 deg there, for the corners' sake).
  const auto beyondLeftEdge = [&](double deg) {
    const glm::dvec2 t(-std::tan(std::atan(double(s.field.left)) + glm::radians(deg)), 0.0);
    const glm::dvec2 p = tanToEyeBuffer(s.fov, s.width, s.height, t);
    return at(s, int(p.x), int(p.y));
  };
  EXPECT_EQ(density[beyondLeftEdge(1.0)], lowest);
  EXPECT_EQ(hidden[beyondLeftEdge(2.5)], 1);
  EXPECT_GT(highest, 2.0f * lowest);
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
