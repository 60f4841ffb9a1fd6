// Fusion on synthetic streams decoded through SensorStream, as the driver does.
#include "hmd/fusion.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "hmd/synthetic.h"

namespace photovr::hmd {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Noise like a DK2 at rest: gyro ~0.005 rad/s, accel ~0.05 m/s^2 per sample and axis.
MotionScript noisy(MotionScript s) {
  s.gyroNoise = 0.005;
  s.accelNoise = 0.05;
  s.seed = 7;
  return s;
}

double angleBetween(const glm::dquat& a, const glm::dquat& b) {
  return 2.0 * std::acos(std::min(1.0, std::abs(glm::dot(a, b))));
}

double yawOf(const glm::dquat& q) {
  const glm::dvec3 f = q * glm::dvec3(0, 0, -1);
  return std::atan2(-f.x, -f.z);
}

// Feeds a stream, calling 'each' after every report with the filter and the truth.
template <class F>
OrientationFilter run(const SyntheticStream& stream, FusionSettings settings, F each) {
  SensorStream decoder;
  OrientationFilter filter(settings);
  for (size_t i = 0; i < stream.reports.size(); ++i) {
    for (const ImuSample& s : decoder.push(stream.reports[i])) filter.update(s);
    each(filter, stream.truth[i], stream.reportTimes[i]);
  }
  return filter;
}

OrientationFilter run(const SyntheticStream& stream, FusionSettings settings = {}) {
  return run(stream, settings, [](auto&, auto&, double) {});
}

TEST(Fusion, StillHeadsetAtAKnownTiltConvergesWithinHalfADegreeInUnderTwoSeconds) {
  MotionScript script;
  // 25 deg pitch and 15 deg roll, with heading 40 deg (yaw is not observable from gravity).
  script.start = glm::angleAxis(40 * kDeg, glm::dvec3(0, 1, 0)) *
                 glm::angleAxis(25 * kDeg, glm::dvec3(1, 0, 0)) *
                 glm::angleAxis(15 * kDeg, glm::dvec3(0, 0, 1));
  script.segments = {{2.0, {}}};
  const SyntheticStream stream = synthesize(noisy(script));
  FusionSettings settings;
  settings.alignOnFirstSample = false;  // start level: convergence by the filter alone
  double convergedAt = -1.0;
  run(stream, settings, [&](const OrientationFilter& f, const glm::dquat& truth, double t) {
    const glm::dvec3 upErr = f.orientation() * (glm::conjugate(truth) * glm::dvec3(0, 1, 0));
    const double tilt = std::acos(std::min(1.0, upErr.y));
    if (tilt > 0.5 * kDeg)
      convergedAt = -1.0;
    else if (convergedAt < 0)
      convergedAt = t;
  });
  // Still time constant 0.2 s after 0.5 s of stillness: 29 deg -> 0.5 deg by ~1.3 s.
  ASSERT_GE(convergedAt, 0.0) << "never converged";
  EXPECT_LT(convergedAt, 2.0);
}

TEST(Fusion, FirstSampleAlignmentIsImmediate) {
  MotionScript script;
  script.start = glm::angleAxis(30 * kDeg, glm::dvec3(1, 0, 0));
  script.segments = {{0.01, {}}};
  const OrientationFilter f = run(synthesize(noisy(script)));
  // One accel sample with 0.05 m/s^2 noise: ~0.005 rad of tilt error, 3x margin.
  EXPECT_LT(angleBetween(f.orientation(), script.start), 0.015);
}

TEST(Fusion, ConstantYawRateIntegratesToTheRightAngle) {
  for (int perReport : {1, 2, 5}) {
    MotionScript script;
    script.segments = {{0.2, {}}, {1.5, {0, 1.0, 0}}, {0.1, {}}};  // 1.5 rad turn
    script.samplesPerReport = perReport;
    const OrientationFilter f = run(synthesize(noisy(script)));
    // 0.5 % of 1.5 rad; noise contributes 0.005 rad/s * sqrt(1.7 s * 1 ms) ~ 2e-4 rad.
    EXPECT_NEAR(yawOf(f.orientation()), 1.5, 0.005 * 1.5) << perReport << " samples/report";
  }
}

TEST(Fusion, GyroBiasIsLearnedWhileStillAndStopsTheDrift) {
  MotionScript script;
  script.start = glm::angleAxis(10 * kDeg, glm::dvec3(1, 0, 0));
  script.segments = {{4.0, {}}, {0.5, {0.8, 0.5, 0}}, {10.0, {}}};
  script.gyroBias = {0.01, -0.02, 0.015};  // rad/s, ~1 deg/s: larger than a DK2's
  const SyntheticStream stream = synthesize(noisy(script));
  double yawAfterMotion = 0.0;
  const OrientationFilter f =
      run(stream, {}, [&](const OrientationFilter& fl, const glm::dquat&, double t) {
        if (std::abs(t - 4.6) < 5e-4) yawAfterMotion = yawOf(fl.orientation());
      });
  // Running mean over >= 3.5 s of stillness: noise 0.005/sqrt(3500) ~ 1e-4 rad/s plus the
  // 1e-4 rad/s quantisation of the gyro; 5e-4 leaves margin for both.
  EXPECT_NEAR(f.gyroBias().x, 0.01, 5e-4);
  EXPECT_NEAR(f.gyroBias().y, -0.02, 5e-4);
  EXPECT_NEAR(f.gyroBias().z, 0.015, 5e-4);
  // Uncorrected, the 0.02 rad/s yaw bias would drift 11 deg over the last 10 s.
  EXPECT_NEAR(yawOf(f.orientation()), yawAfterMotion, 0.5 * kDeg);
  EXPECT_LT(angleBetween(f.orientation(), stream.finalOrientation), 1.0 * kDeg);
}

TEST(Fusion, SlowTurnIsNotMistakenForBias) {
  MotionScript script;
  script.segments = {{1.0, {}}, {3.0, {0, 0.2, 0}}};  // 11 deg/s, above the still threshold
  const OrientationFilter f = run(synthesize(noisy(script)));
  EXPECT_NEAR(f.gyroBias().y, 0.0, 5e-4);
  EXPECT_NEAR(yawOf(f.orientation()), 0.6, 0.005 * 0.6);
}

TEST(Fusion, TimestampWrapAndDroppedPacketsKeepTheIntegral) {
  MotionScript script;
  script.segments = {{0.1, {}}, {1.0, {0, 1.2, 0}}, {0.1, {}}};
  script.startTimestampUs = 0xFFFFFFFFu - 500000;  // wraps 0.5 s in
  script.startSampleCount = 65000;                 // and so does SampleCount
  script.samplesPerReport = 2;
  script.dropped = {{0.3, 0.31}, {0.6, 0.65}, {0.8, 0.802}};  // lost USB packets
  const SyntheticStream stream = synthesize(noisy(script));
  SensorStream decoder;
  OrientationFilter f;
  for (const ReportBytes& r : stream.reports)
    for (const ImuSample& s : decoder.push(r)) f.update(s);
  EXPECT_EQ(decoder.stats().rejectedTotal(), 0u);
  EXPECT_EQ(decoder.stats().droppedSamples, 10u + 50u + 2u);
  // Gaps during a constant rate are bridged exactly (the held rate is the true one).
  EXPECT_NEAR(yawOf(f.orientation()), 1.2, 0.005 * 1.2);
}

TEST(Fusion, PredictionAheadMatchesTheFutureOrientation) {
  MotionScript script;
  script.segments = {{0.3, {0.5, 2.0, -0.3}}};
  script.seed = 3;
  const SyntheticStream stream = synthesize(script);  // noise-free: prediction error only
  SensorStream decoder;
  OrientationFilter f;
  const size_t at = stream.reports.size() - 1 - 21;  // 21 reports (ms) before the end
  for (size_t i = 0; i <= at; ++i)
    for (const ImuSample& s : decoder.push(stream.reports[i])) f.update(s);
  const glm::dquat future = stream.truth[at + 21];
  // Constant rate: prediction is exact up to tilt correction and 1e-4 rad/s quantisation.
  EXPECT_LT(angleBetween(f.predict(0.021), future), 0.05 * kDeg);
  EXPECT_GT(angleBetween(f.orientation(), future), 2.0 * kDeg);     // it did need predicting
  EXPECT_LT(angleBetween(f.predict(10.0), f.predict(0.1)), 1e-12);  // horizon capped
}

TEST(Fusion, IntegrateGyroIsExactForAConstantRate) {
  const glm::dvec3 w(0.3, -0.7, 1.1);
  glm::dquat q(1, 0, 0, 0);
  for (int i = 0; i < 1000; ++i) q = integrateGyro(q, w, 1e-3);
  const glm::dquat exact = glm::angleAxis(glm::length(w), glm::normalize(w));
  EXPECT_LT(angleBetween(q, exact), 1e-10);  // 1000 double roundings
}

}  // namespace
}  // namespace photovr::hmd
