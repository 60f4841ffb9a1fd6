#include "core/camera.h"

#include <cmath>
#include <limits>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>
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

TEST(CameraRays, ThroughCentreIsTheUnjitteredCentreRay) {
  // The partner search intersects this ray with a plane: it must point through the pixel's
  // centre (not its jittered sample) whatever its length. Unit vectors, float rounding.
  const EyeCamera cam = testEye({0.3f, -0.2f});
  const CameraRays rays(cam);
  for (glm::ivec2 p : {glm::ivec2(0, 0), glm::ivec2(480, 540), glm::ivec2(959, 1079)}) {
    const glm::vec3 d = glm::normalize(rays.throughCentre(p.x, p.y));
    const glm::vec3 e = cam.rayDirection(p.x + 0.5f, p.y + 0.5f);
    EXPECT_NEAR(glm::length(d - e), 0.0f, 1e-6f) << p.x << ", " << p.y;
  }
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

TEST(FovTangents, WidenedHoldsEveryDirectionWithinTheAngleOfTheField) {
  const FovTangents f = FovTangents::dk2LeftEye();
  const double a = glm::radians(3.0);
  const FovTangents w = f.widened(float(a));
  // Directions at exactly 'a' from the field's boundary, all around it: each must fall inside
  // 'w', and for each edge one of them must touch it (float: 1e-5 relative).
  double reach[4] = {0, 0, 0, 0};  // left, right, up, down
  for (int i = 0; i <= 400; ++i) {
    const double s = i / 400.0;
    for (glm::dvec2 t : {glm::dvec2(-f.left, -f.down + s * (f.up + f.down)),
                         glm::dvec2(f.right, -f.down + s * (f.up + f.down)),
                         glm::dvec2(-f.left + s * (f.left + f.right), f.up),
                         glm::dvec2(-f.left + s * (f.left + f.right), -f.down)}) {
      const glm::dvec3 d = glm::normalize(glm::dvec3(t, -1.0));
      for (int k = 0; k < 64; ++k) {  // every way of turning 'a' away from d
        const glm::dvec3 side = glm::normalize(glm::cross(d, glm::dvec3(1, 2, 3)));
        const glm::dvec3 axis = glm::angleAxis(k * 2 * glm::pi<double>() / 64, d) * side;
        const glm::dvec3 e = glm::angleAxis(a, axis) * d;
        const glm::dvec2 te = glm::dvec2(e) / -e.z;
        reach[0] = std::max(reach[0], -te.x), reach[1] = std::max(reach[1], te.x);
        reach[2] = std::max(reach[2], te.y), reach[3] = std::max(reach[3], -te.y);
      }
    }
  }
  const double edge[4] = {w.left, w.right, w.up, w.down};
  for (int i = 0; i < 4; ++i) {
    EXPECT_LE(reach[i], edge[i] * (1 + 1e-5)) << i;
    EXPECT_GT(reach[i], edge[i] * (1 - 2e-3)) << i;  // 64 turn directions: ~1e-3 short
  }
  // The corners make it more than turning each edge out by the angle.
  EXPECT_GT(w.left, std::tan(std::atan(f.left) + a));
}

TEST(StereoLayout, OverscanGrowsTheBufferAtTheFieldsPixelDensity) {
  const StereoLayout plain = StereoLayout::dk2(960, 1080);
  EXPECT_EQ(plain.width, 960);
  EXPECT_EQ(plain.height, 1080);
  EXPECT_EQ(plain.leftFov.left, FovTangents::dk2LeftEye().left);
  const StereoLayout over = StereoLayout::dk2(960, 1080, glm::radians(2.0f));
  // Pixels per tan-angle as the field's, to the one pixel the size is rounded up by.
  const FovTangents f = FovTangents::dk2LeftEye(), w = over.leftFov;
  EXPECT_NEAR(over.width / (w.left + w.right), 960 / (f.left + f.right), 1.0 / (w.left + w.right));
  EXPECT_NEAR(over.height / (w.up + w.down), 1080 / (f.up + f.down), 1.0 / (w.up + w.down));
  EXPECT_GT(over.width, 1000);                    // 2 deg at tan ~1.1 adds ~36 pixels a side
  EXPECT_EQ(over.fov(Eye::Right).left, w.right);  // the right eye mirrors the left
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
