#include "hmd/desktop_camera.h"

#include <cmath>

#include <gtest/gtest.h>

namespace photovr::hmd {
namespace {

TEST(DesktopCamera, WalksForwardAlongTheHeading) {
  DesktopCamera c;
  c = step(c, {.forward = true, .dt = 1.0f});
  EXPECT_NEAR(c.position.z, -1.5f, 1e-6f);                             // default 1.5 m/s down -Z
  c = step(c, {.mouseDelta = {-glm::half_pi<float>() / 0.0025f, 0}});  // turn left 90 deg
  c = step(c, {.forward = true, .dt = 1.0f});
  EXPECT_NEAR(c.position.x, -1.5f, 1e-4f);
  EXPECT_NEAR(c.position.z, -1.5f, 1e-4f);
}

TEST(DesktopCamera, DiagonalsAreNotFasterAndShiftIsFast) {
  const DesktopCamera c = step({}, {.forward = true, .right = true, .fast = true, .dt = 0.5f});
  EXPECT_NEAR(glm::length(c.position), 1.5f * 4.0f * 0.5f, 1e-5f);
}

TEST(DesktopCamera, PitchClampsAndDraggingDownLooksDown) {
  DesktopCamera c = step({}, {.mouseDelta = {0, 100}});
  EXPECT_LT((c.pose().orientation * glm::vec3(0, 0, -1)).y, 0.0f);
  c = step(c, {.mouseDelta = {0, 1e6f}});
  EXPECT_NEAR(c.pitch, -glm::radians(89.0f), 1e-6f);
}

TEST(DesktopCamera, RoundTripsThroughAPose) {
  DesktopCamera c;
  c.position = {1, 2, 3};
  c.yaw = 0.7f;
  c.pitch = -0.3f;
  const DesktopCamera back = DesktopCamera::from(c.pose());
  EXPECT_NEAR(back.yaw, c.yaw, 1e-5f);
  EXPECT_NEAR(back.pitch, c.pitch, 1e-5f);
  EXPECT_EQ(back.position, c.position);
}

}  // namespace
}  // namespace photovr::hmd
