// The numerical stress suite, quick variants (the full run is `photovr stress`).
#include "hybrid/stress.h"

#include <gtest/gtest.h>

#include "tests/gl/gl_test_util.h"

namespace photovr {
namespace {

TEST(StressSuite, EveryCasePasses) {
  testing::osmesaContext();
  const std::vector<StressResult> results = runStressSuite(true);
  std::printf("%s", formatStressReport(results).c_str());
  for (const StressResult& r : results) {
    EXPECT_EQ(r.nonFinitePixels, 0u) << r.name;
    EXPECT_EQ(r.rejectedSamples, 0u) << r.name;  // valid input never produces NaN/Inf
    EXPECT_LE(r.relMseVsReference, r.maxRelMse) << r.name;
    EXPECT_LE(r.relMseHybridVsPt, r.maxHybridVsPt) << r.name;
  }
}

}  // namespace
}  // namespace photovr
