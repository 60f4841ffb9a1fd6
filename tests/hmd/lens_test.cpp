// The DK2 lens model (dk2.md §6): spline, round trip, implied FOV.
#include "hmd/lens.h"

#include <cmath>

#include <gtest/gtest.h>

namespace photovr::hmd {
namespace {

const LensModel kDk2;

TEST(Lens, SplinePassesThroughTheKnotsAndContinuesLinearly) {
  const auto& k = kDk2.lens.k;
  EXPECT_DOUBLE_EQ(catmullRom10(k, 0.0), 1.0);  // segment 0 starts at 1 (dk2.md §6)
  for (int i = 1; i <= 10; ++i) EXPECT_NEAR(catmullRom10(k, i), k[i], 1e-12) << i;
  EXPECT_NEAR(catmullRom10(k, 12.5), k[10] + 2.5 * (k[10] - k[9]), 1e-12);
  // C1 at interior knots: the Catmull-Rom tangents are shared by both segments.
  for (int i = 1; i < 10; ++i) {
    const double h = 1e-6;
    const double left = (catmullRom10(k, i) - catmullRom10(k, i - h)) / h;
    const double right = (catmullRom10(k, i + h) - catmullRom10(k, i)) / h;
    EXPECT_NEAR(left, right, 1e-4) << i;  // finite differences err ~h * f''
  }
}

TEST(Lens, CentreAndScaleMatchTheReference) {
  // dk2.md §6: lens centre (-0.00986, 0) left, (+0.00986, 0) right; scale (0.8733, 0.9825).
  EXPECT_NEAR(lensCentre(kDk2.panel, Eye::Left).x, -0.00986, 1e-5);
  EXPECT_NEAR(lensCentre(kDk2.panel, Eye::Right).x, 0.00986, 1e-5);
  EXPECT_NEAR(lensCentre(kDk2.panel, Eye::Left).y, 0.0, 1e-12);
  EXPECT_NEAR(screenToLensScale(kDk2).x, 0.8733, 1e-4);
  EXPECT_NEAR(screenToLensScale(kDk2).y, 0.9825, 1e-4);
  // dk2.md §5: 549.6 display pixels per tan-angle at the centre (480 px per NDC unit).
  EXPECT_NEAR(480.0 / screenToLensScale(kDk2).x, 549.6, 0.1);
}

TEST(Lens, DistortionThenInverseRoundTripsAcrossTheField) {
  double worst = 0.0;
  for (Eye eye : {Eye::Left, Eye::Right})
    for (Channel c : {Channel::Red, Channel::Green, Channel::Blue})
      for (double y = -1.3; y <= 1.3; y += 0.05)
        for (double x = -1.1; x <= 1.1; x += 0.05) {
          const glm::dvec2 tan(x, y);
          const glm::dvec2 back = screenToTan(kDk2, eye, tanToScreen(kDk2, eye, tan, c), c);
          worst = std::max(worst, glm::length(back - tan));
        }
  EXPECT_LT(worst, 1e-4);  // issue 6's bound; Newton reaches ~1e-12
  EXPECT_LT(worst, 1e-9);
}

TEST(Lens, ScreenToTanIsRadialAndGrowsFasterThanLinear) {
  const glm::dvec2 c = lensCentre(kDk2.panel, Eye::Left);
  const glm::dvec2 near = screenToTan(kDk2, Eye::Left, c + glm::dvec2(0.1, 0));
  const glm::dvec2 far = screenToTan(kDk2, Eye::Left, c + glm::dvec2(0.9, 0));
  EXPECT_NEAR(near.y, 0.0, 1e-12);
  EXPECT_GT(far.x / 0.9, near.x / 0.1);  // the periphery is stretched (pincushion in tan)
}

TEST(Lens, ChromaticTermsSpreadRedInAndBlueOut) {
  const glm::dvec2 p(0.7, 0.5);
  const double g = glm::length(screenToTan(kDk2, Eye::Left, p, Channel::Green));
  EXPECT_LT(glm::length(screenToTan(kDk2, Eye::Left, p, Channel::Red)), g);
  EXPECT_GT(glm::length(screenToTan(kDk2, Eye::Left, p, Channel::Blue)), g);
}

TEST(Lens, ImpliedFovMatchesTheLibOvrDefaults) {
  const FovTangents left = lensFov(kDk2, Eye::Left);
  const FovTangents ref = FovTangents::dk2LeftEye();
  // LibOVR 0.4 derives its defaults with eye relief and rounding of its own; 0.5 % covers it.
  EXPECT_NEAR(left.left, ref.left, 0.005 * ref.left);
  EXPECT_NEAR(left.right, ref.right, 0.005 * ref.right);
  EXPECT_NEAR(left.up, ref.up, 0.005 * ref.up);
  EXPECT_NEAR(left.down, ref.down, 0.005 * ref.down);
  const FovTangents right = lensFov(kDk2, Eye::Right);
  EXPECT_FLOAT_EQ(right.left, left.right);  // mirrored
  EXPECT_FLOAT_EQ(right.right, left.left);
}

TEST(Lens, EyeBufferMappingInvertsAndMatchesTheCamera) {
  const FovTangents fov = FovTangents::dk2LeftEye();
  const glm::dvec2 px(100.25, 700.5);
  const glm::dvec2 t = eyeBufferToTan(fov, 1182, 1461, px);
  const glm::dvec2 back = tanToEyeBuffer(fov, 1182, 1461, t);
  EXPECT_NEAR(back.x, px.x, 1e-9);
  EXPECT_NEAR(back.y, px.y, 1e-9);
  EyeCamera cam;
  cam.fov = fov;
  cam.width = 1182, cam.height = 1461;
  const glm::vec3 d = cam.rayDirection(float(px.x), float(px.y));
  EXPECT_NEAR(d.x / -d.z, t.x, 1e-5);  // float camera vs double lens: ~1e-6
  EXPECT_NEAR(d.y / -d.z, t.y, 1e-5);
}

}  // namespace
}  // namespace photovr::hmd
