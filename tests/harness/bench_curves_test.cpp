// The bench's equal-time and equal-error figures (harness/bench_run.h): log-log interpolation
// of an error-vs-time curve, exact for the power laws Monte Carlo error follows.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "harness/bench_run.h"

namespace photovr::harness {
namespace {

// relMSE = k / t^p at t = 10, 20, 40, 80 ms.
std::vector<FrameRecord> powerLaw(double k, double p) {
  std::vector<FrameRecord> c;
  for (double t : {10.0, 20.0, 40.0, 80.0}) {
    FrameRecord f;
    f.elapsedMs = t;
    f.relMse = k / std::pow(t, p);
    c.push_back(f);
  }
  return c;
}

// Log-log interpolation of a power law is exact up to double rounding: 1e-12 relative.
constexpr double kExact = 1e-12;

TEST(BenchCurves, InterpolationIsExactOnAPowerLaw) {
  for (double p : {1.0, 0.5, 2.0}) {
    const auto c = powerLaw(3.0, p);
    for (double t : {12.0, 25.0, 63.0}) {
      const double e = 3.0 / std::pow(t, p);
      EXPECT_NEAR(errorAtTime(c, t), e, kExact * e) << p;
      EXPECT_NEAR(timeToError(c, e), t, kExact * t) << p;
    }
  }
}

TEST(BenchCurves, OutsideTheCurveErrorFallsAsOneOverTime) {
  const auto c = powerLaw(3.0, 1.0);                        // relMSE = 3 / t
  EXPECT_NEAR(errorAtTime(c, 160.0), 3.0 / 160.0, kExact);  // beyond the last frame
  EXPECT_NEAR(errorAtTime(c, 5.0), 3.0 / 5.0, kExact);      // before the first
  EXPECT_NEAR(timeToError(c, 3.0 / 320.0), 320.0, 320.0 * kExact);
  EXPECT_NEAR(timeToError(c, 3.0 / 2.0), 2.0, 2.0 * kExact);
}

TEST(BenchCurves, EmptyCurveNeverReachesAnError) {
  EXPECT_TRUE(std::isinf(timeToError({}, 0.1)));
  EXPECT_TRUE(std::isinf(errorAtTime({}, 10.0)));
}

}  // namespace
}  // namespace photovr::harness
