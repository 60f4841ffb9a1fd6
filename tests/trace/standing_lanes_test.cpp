// Stereo reuse's standing pixels in lanes (trace/standing_lanes.h) are standingPixelOf's,
// bit for bit, for right samples anywhere: in front of and behind the left eye, on planes
// seen head-on and at grazing angles (the centre ray's plane point beyond kCentreReach),
// projecting inside and outside the left image, on glass, and with degenerate normals.
#include "trace/standing_lanes.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "tests/trace/trace_test_util.h"

namespace photovr {
namespace {

TEST(StandingLanes, GiveTheScalarStandingPixelsBitForBit) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), u01(0.0f, 1.0f);
  size_t found = 0, none = 0, total = 0;
  for (int k = 0; k < 30; ++k) {
    EyeWindow left;
    left.set(testing::randomEyeCamera(rng, 4.0f), 1);  // looking near -Z
    const glm::vec3 eye = left.camera.pose.position + glm::vec3(0.0635f, 0.01f * u(rng), 0.0f);
    const glm::vec2 offset(0.5f * u(rng), 0.5f * u(rng));
    const size_t n = 1 + rng() % 70;  // ragged ends of the groups of eight
    std::vector<SurfaceHit> hits(n);
    std::vector<glm::vec3> centreRays(n);
    std::vector<StandingPixel> lanes(n);
    std::vector<StandingJob> jobs(n);
    for (size_t i = 0; i < n; ++i) {
      SurfaceHit& h = hits[i];
      // Mostly ahead of the eyes (-z), some behind; normals anywhere, some zero.
      h.position = eye + glm::vec3(2.0f * u(rng), 2.0f * u(rng), -3.0f * u01(rng) + 0.3f);
      const float pick = u01(rng);
      h.geometricNormal =
          pick < 0.05f ? glm::vec3(0.0f) : glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
      h.bsdf.transmission = u01(rng) < 0.1f ? 1.0f : 0.0f;
      // The ray through the pixel centre: near the hit's direction, or grazing its plane.
      const glm::vec3 toHit = glm::normalize(h.position - eye);
      centreRays[i] = u01(rng) < 0.2f
                          ? glm::normalize(glm::cross(h.geometricNormal, toHit) + 1e-3f * toHit)
                          : toHit + 0.01f * glm::vec3(u(rng), u(rng), u(rng));
      jobs[i] = {&hits[i], centreRays[i], &lanes[i]};
    }
    standingPixelsOf(left, eye, offset, jobs);
    for (size_t i = 0; i < n; ++i) {
      const StandingPixel s = standingPixelOf(left, hits[i], {eye, centreRays[i], offset, 0});
      ASSERT_EQ(lanes[i].pixel, s.pixel) << "window " << k << ", sample " << i;
      ASSERT_EQ(std::memcmp(&lanes[i].footprint2, &s.footprint2, sizeof(float)), 0)
          << "window " << k << ", sample " << i << ": " << lanes[i].footprint2 << " against "
          << s.footprint2;
      (s.pixel == kNoLeftPixel ? none : found) += 1;
      ++total;
    }
  }
  // Both answers occur often enough for the comparison to mean something.
  EXPECT_GT(found, total / 5);
  EXPECT_GT(none, total / 10);
}

}  // namespace
}  // namespace photovr
