#include "core/camera.h"

#include <limits>

#include <gtest/gtest.h>

namespace photovr {
namespace {

// Single-precision matrix products of values ~1..10 round to a few ulp of the result;
// 1e-4 pixels on a 960-pixel image is ~1e-7 relative, a few float ulps.
constexpr float kPixelTol = 2e-3f;

glm::vec2 toWindow(const EyeCamera& cam, const glm::vec3& world, float* depth = nullptr) {
  const glm::vec4 clip = cam.projection() * cam.view() * glm::vec4(world, 1.0f);
  const glm::vec3 ndc = glm::vec3(clip) / clip.w;
  if (depth) *depth = ndc.z;
  return (glm::vec2(ndc) * 0.5f + 0.5f) * glm::vec2(cam.width, cam.height);
}

EyeCamera testEye(glm::vec2 jitter) {
  StereoRig rig;
  rig.head = lookAt({1, 2, 3}, {0, 1, -4});
  return rig.eye(Eye::Right, 960, 1080, jitter);
}

TEST(EyeCamera, RayThroughSampleProjectsToPixelCentreWithJitter) {
  const EyeCamera cam = testEye({0.3f, -0.2f});
  for (glm::ivec2 p : {glm::ivec2(0, 0), glm::ivec2(480, 540), glm::ivec2(959, 1079)}) {
    const glm::vec3 world = cam.pose.position + 7.0f * cam.pixelRay(p.x, p.y);
    const glm::vec2 w = toWindow(cam, world);
    EXPECT_NEAR(w.x, p.x + 0.5f, kPixelTol);
    EXPECT_NEAR(w.y, p.y + 0.5f, kPixelTol);
  }
}

TEST(EyeCamera, LinearRayFormMatchesNormalisedDirection) {
  const EyeCamera cam = testEye({0.1f, 0.4f});
  const glm::vec3 d = glm::normalize(cam.rayBase() + 100.5f * cam.rayDx() + 7.25f * cam.rayDy());
  const glm::vec3 e = cam.rayDirection(100.5f, 7.25f);
  EXPECT_NEAR(glm::length(d - e), 0.0f, 1e-6f);  // unit vectors, float rounding
}

TEST(EyeCamera, ReversedZDepthIsNearOverDistance) {
  EyeCamera cam = testEye({0, 0});
  const glm::vec3 forward = cam.pose.orientation * glm::vec3(0, 0, -1);
  for (float d : {0.05f, 1.0f, 13.0f, 1000.0f}) {
    float depth = 0;
    toWindow(cam, cam.pose.position + d * forward, &depth);
    // The point is formed in world coordinates of magnitude |p|, so its view distance
    // carries an absolute rounding error of a few ulp of |p|: relative error ~ eps |p| / d.
    const float eps = std::numeric_limits<float>::epsilon();
    const float rel = 8.0f * eps * (1.0f + glm::length(cam.pose.position) / d);
    EXPECT_NEAR(depth, cam.znear / d, rel * (cam.znear / d)) << d;
    EXPECT_FLOAT_EQ(cam.depthAt(d), cam.znear / d);
  }
  cam.zfar = 100.0f;
  float depth = 0;
  toWindow(cam, cam.pose.position + 100.0f * forward, &depth);
  EXPECT_NEAR(depth, 0.0f, 1e-6f);
  toWindow(cam, cam.pose.position + cam.znear * forward, &depth);
  EXPECT_NEAR(depth, 1.0f, 1e-5f);  // same world-space rounding at d = near (|p|/d ~ 80)
}

TEST(StereoRig, EyesAreIpdApartAlongHeadX) {
  StereoRig rig;
  rig.head = lookAt({0, 1.7f, 0}, {3, 1.7f, -3});
  const EyeCamera l = rig.eye(Eye::Left, 10, 10), r = rig.eye(Eye::Right, 10, 10);
  EXPECT_NEAR(glm::distance(l.pose.position, r.pose.position), kDefaultIpd, 1e-6f);
  const glm::vec3 headX = rig.head.orientation * glm::vec3(1, 0, 0);
  EXPECT_NEAR(glm::dot(r.pose.position - l.pose.position, headX), kDefaultIpd, 1e-6f);
  EXPECT_EQ(l.fov.left, r.fov.right);  // mirrored: outer <-> nasal
}

TEST(Halton, FirstPointsOfBases2And3) {
  EXPECT_FLOAT_EQ(radicalInverse(2, 1), 0.5f);
  EXPECT_FLOAT_EQ(radicalInverse(2, 3), 0.75f);
  EXPECT_FLOAT_EQ(radicalInverse(3, 1), 1.0f / 3.0f);
  EXPECT_FLOAT_EQ(radicalInverse(3, 5), 2.0f / 3.0f + 1.0f / 9.0f);
  const glm::vec2 j = haltonJitter(0);
  EXPECT_FLOAT_EQ(j.x, 0.0f);
  EXPECT_FLOAT_EQ(j.y, 1.0f / 3.0f - 0.5f);
}

TEST(LookAt, ForwardPointsAtTarget) {
  const Pose p = lookAt({1, 1, 1}, {4, 5, 1});
  const glm::vec3 f = p.orientation * glm::vec3(0, 0, -1);
  EXPECT_NEAR(glm::distance(f, glm::vec3(0.6f, 0.8f, 0.0f)), 0.0f, 1e-6f);
}

}  // namespace
}  // namespace photovr
