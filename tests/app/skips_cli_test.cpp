// render --no-skip and --converge from the command line: names checked, work reported.
#include <gtest/gtest.h>

#include <string>

#include "tests/app/cli_util.h"

namespace photovr {
namespace {

using testing::runPhotovr;
using testing::tempDir;

TEST(SkipsCli, UnknownSkipIsAUsageErrorListingTheNames) {
  const auto r =
      runPhotovr("render --scene cornell --no-skip refit,bogus --out " + tempDir("skips-bad"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("'bogus'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("sky-pixels"), std::string::npos) << r.output;
}

TEST(SkipsCli, AllSkipsOffStillRenders) {
  const auto r = runPhotovr(
      "render --scene cornell --mode pt --width 16 --height 18 --no-skip "
      "all --out " +
      tempDir("skips-all"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("0 samples rejected"), std::string::npos) << r.output;
}

TEST(SkipsCli, ConvergedAccumulationStopsEarly) {
  // 16 x 18 cornell at 4 spp: the estimated relMSE is ~0.15 / frames (measured), so 0.02 is
  // reached after about 8 frames: later than the earliest stop (kMinFrames = 4), far before 64.
  const auto r = runPhotovr(
      "render --scene cornell --mode pt --eyes mono --width 16 --height 18 "
      "--spp 4 --frames 64 --converge 0.02 --out " +
      tempDir("converge"));
  EXPECT_EQ(r.status, 0) << r.output;
  const size_t at = r.output.find("converged after ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const int frames = std::stoi(r.output.substr(at + 16));
  EXPECT_GT(frames, 4) << r.output;
  EXPECT_LT(frames, 64) << r.output;
  EXPECT_NE(r.output.find("x " + std::to_string(frames) + " frames"), std::string::npos)
      << r.output;
  EXPECT_EQ(
      runPhotovr("render --scene cornell --converge 2 --out " + tempDir("converge-bad")).status, 2);
}

}  // namespace
}  // namespace photovr
