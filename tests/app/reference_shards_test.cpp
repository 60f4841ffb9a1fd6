// Issue 24: a reference split into shard jobs (harness/reference_shards.h) and run through
// GNU parallel (scripts/cluster/reference_parallel.sh) equals the unsharded reference bit
// for bit; a shard cut short and run again completes it; jobs running the same shards at
// once leave a valid reference. Pixels are compared exactly (the EXR headers carry a date).
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>

#include "core/image_io.h"
#include "tests/app/cli_util.h"

namespace photovr {
namespace {

using testing::runCommand;
using testing::runPhotovr;
using testing::tempDir;

namespace fs = std::filesystem;

// 16 frames of 4 spp of a small view: enough frames for 4 shards of 4, quick on 2 cores.
const std::string kArgs =
    " --scene cornell --width 16 --height 16 --bounces 2 --spp 64 --backend osmesa --eyes mono";

std::string script() {
  return std::string(PHOTOVR_SOURCE_DIR) + "/scripts/cluster/reference_parallel.sh";
}

// The one reference folder a cache holds.
std::string referenceDir(const std::string& cache) {
  std::string found;
  for (const auto& e : fs::directory_iterator(cache + "/references")) found = e.path().string();
  return found;
}

bool samePixels(const std::string& a, const std::string& b) {
  const ImageF x = readImageF(a), y = readImageF(b);
  return x.width == y.width && x.height == y.height && x.channels == y.channels &&
         std::memcmp(x.data.data(), y.data.data(), x.data.size() * sizeof(float)) == 0;
}

// Each test its own folder: ctest runs them at once.
std::string unshardedReference(const std::string& test) {
  const std::string cache = tempDir("shards-unsharded-" + test);
  const auto r = runPhotovr("reference" + kArgs, "PHOTOVR_CACHE_DIR=" + cache);
  EXPECT_EQ(r.status, 0) << r.output;
  return referenceDir(cache) + "/eye0.exr";
}

std::string parallelRun(const std::string& cache, int shards, int jobs) {
  const auto r = runCommand(script() + " " + std::to_string(shards) + " " + std::to_string(jobs) +
                            " " + cache + " " + PHOTOVR_BINARY + kArgs);
  EXPECT_EQ(r.status, 0) << r.output;
  return r.output;
}

bool haveParallel() {
  return runCommand("command -v parallel").status == 0;
}

TEST(ReferenceShards, FourShardsThroughGnuParallelEqualTheUnshardedReference) {
  if (!haveParallel()) GTEST_SKIP() << "GNU parallel missing (scripts/setup.sh installs it)";
  const std::string unsharded = unshardedReference("parallel");
  const std::string cache = tempDir("shards-parallel");
  const std::string out = parallelRun(cache, 4, 2);
  EXPECT_NE(out.find("64 spp"), std::string::npos) << out;  // one job merged the set
  EXPECT_TRUE(samePixels(referenceDir(cache) + "/eye0.exr", unsharded));
  // The power of the comparison: a reference of other frames (15, not 16) differs.
  const std::string fewer = tempDir("shards-fewer");
  const std::string fewerArgs =
      " --scene cornell --width 16 --height 16 --bounces 2 --spp 60 --backend osmesa --eyes mono";
  ASSERT_EQ(runPhotovr("reference" + fewerArgs, "PHOTOVR_CACHE_DIR=" + fewer).status, 0);
  EXPECT_FALSE(samePixels(referenceDir(fewer) + "/eye0.exr", unsharded));
}

// A shard stopped after part of its frames (here: asked for fewer first, which saves what a
// kill after those frames leaves) continues when run again; a corrupt shard file starts
// that shard over. Both end at the unsharded reference.
TEST(ReferenceShards, InterruptedAndCorruptShardsCompleteTheSameReference) {
  if (!haveParallel()) GTEST_SKIP() << "GNU parallel missing (scripts/setup.sh installs it)";
  const std::string unsharded = unshardedReference("resumed");
  const std::string cache = tempDir("shards-resumed");
  const std::string partial =
      " --scene cornell --width 16 --height 16 --bounces 2 --spp 32 --backend osmesa --eyes mono";
  auto r = runPhotovr("reference" + partial + " --shard 2/4", "PHOTOVR_CACHE_DIR=" + cache);
  ASSERT_EQ(r.status, 0) << r.output;
  r = runPhotovr("reference" + kArgs + " --shard 1/4", "PHOTOVR_CACHE_DIR=" + cache);
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string dir = referenceDir(cache);
  fs::resize_file(dir + "/shard-1-of-4.bin", 100);  // cut short: unreadable, starts over
  const std::string out = parallelRun(cache, 4, 2);
  EXPECT_NE(out.find("shard 2/4: 8 -> 16 spp"), std::string::npos) << out;  // resumed
  EXPECT_NE(out.find("shard 1/4: 0 -> 16 spp"), std::string::npos) << out;  // started over
  EXPECT_TRUE(samePixels(dir + "/eye0.exr", unsharded));
}

// Every shard run twice at once on one cache entry: each job writes only its own shard's
// file, atomically, and every merge of the same frames writes the same pixels.
TEST(ReferenceShards, ConcurrentJobsOnOneEntryLeaveAValidReference) {
  if (!haveParallel()) GTEST_SKIP() << "GNU parallel missing (scripts/setup.sh installs it)";
  const std::string unsharded = unshardedReference("concurrent");
  const std::string cache = tempDir("shards-concurrent");
  const auto r =
      runCommand("(" + script() + " 4 4 " + cache + " " + PHOTOVR_BINARY + kArgs + " & " +
                 script() + " 4 4 " + cache + " " + PHOTOVR_BINARY + kArgs + " & wait)");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(samePixels(referenceDir(cache) + "/eye0.exr", unsharded));
  const auto again = runPhotovr("reference" + kArgs, "PHOTOVR_CACHE_DIR=" + cache);
  EXPECT_EQ(again.status, 0) << again.output;
  EXPECT_EQ(again.output.find("->"), std::string::npos) << again.output;  // nothing re-rendered
}

}  // namespace
}  // namespace photovr
