// The numerical stress suite, quick variants (the full run is `photovr stress`). Each case's
// expected images, and the reason for each bound, are where hybrid/stress.cpp makes it.
#include "hybrid/stress.h"

#include <gtest/gtest.h>

#include "tests/gl/gl_test_util.h"

namespace photovr {
namespace {

TEST(StressSuite, EveryCaseMatchesItsExpectedImages) {
  testing::osmesaContext();
  const std::vector<StressResult> results = runStressSuite(true);
  std::printf("%s", formatStressReport(results).c_str());
  ASSERT_EQ(results.size(), 10u);
  for (const StressResult& r : results) {
    EXPECT_EQ(r.nonFinitePixels, 0u) << r.name;
    EXPECT_EQ(r.rejectedSamples, 0u) << r.name;  // valid input never produces NaN/Inf
    // The expected images show the scene, not black: a match is not a match of zeros.
    EXPECT_GT(r.litExpectedPixels, r.pixels / 2) << r.name;
    EXPECT_LE(r.pixelsOffExpected, r.maxPixelsOffExpected) << r.name << " vs " << r.expected;
    if (r.checksHybridVsPt) {
      EXPECT_LE(r.pixelsHybridVsPt, r.maxPixelsHybridVsPt) << r.name;
    }
    EXPECT_TRUE(r.passed) << r.name;
  }
}

}  // namespace
}  // namespace photovr
