// The shard files of a reference (harness/reference_shards.h): which frames a shard takes,
// when a set merges, and that the merge does not depend on how the frames were split.
#include "harness/reference_shards.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "core/error.h"
#include "tests/core/test_dir.h"

namespace photovr::harness {
namespace {

namespace fs = std::filesystem;

std::string freshDir() {
  return testing::freshTestDir("photovr_reference_shards").string();
}

TEST(ReferenceShardFiles, ShardsPartitionTheFrames) {
  for (int total : {0, 1, 7, 16, 17})
    for (int count : {1, 3, 4, 16}) {
      int sum = 0;
      for (int k = 0; k < count; ++k) sum += framesOfShard({k, count}, total);
      EXPECT_EQ(sum, total) << total << " frames in " << count;
    }
  EXPECT_EQ(framesOfShard({3, 4}, 15), 3);  // frames 3, 7, 11
  EXPECT_EQ(framesOfShard({2, 4}, 15), 4);  // frames 2, 6, 10, 14
}

TEST(ReferenceShardFiles, BadShardSpecsAreUsageErrors) {
  for (const char* bad : {"4/4", "-1/4", "1/0", "1/5000", "1", "1/4x", "a/b", ""})
    EXPECT_THROW(parseShard(bad), UsageError) << bad;
  EXPECT_EQ(parseShard("3/8").index, 3);
}

// Frame values of a synthetic 2x1 image: the same 12 frames split 1, 3 and 4 ways, added in
// each shard's order, merge to the same bits; a set with a missing or short shard does not
// merge.
TEST(ReferenceShardFiles, AnySplitMergesToTheSameBits) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 50.0f);
  std::vector<std::vector<glm::vec3>> frames(12, std::vector<glm::vec3>(2));
  for (auto& f : frames)
    for (glm::vec3& p : f) p = glm::vec3(u(rng), u(rng) * 1e-4f, u(rng) * 1e4f);
  const std::string dir = freshDir();
  std::vector<MergedReference> merged;
  for (int count : {1, 3, 4}) {
    for (int k = 0; k < count; ++k) {
      ShardSums s({k, count}, 2, 1, 1);
      for (int i = 0; i < framesOfShard({k, count}, 12); ++i) {
        s.add(0, frames[size_t(k + i * count)]);
        s.frameDone();
      }
      saveShard(dir, s);
    }
    std::optional<MergedReference> m = mergeShards(dir, count, 2, 1, 1);
    ASSERT_TRUE(m) << count;
    EXPECT_EQ(m->frames, 12);
    merged.push_back(*m);
  }
  EXPECT_EQ(merged[0].eyes, merged[1].eyes);
  EXPECT_EQ(merged[0].eyes, merged[2].eyes);
  // The mean itself, to float rounding of the 2^-32 fixed point.
  double mean = 0.0;
  for (const auto& f : frames) mean += f[1].z / 12.0;
  EXPECT_NEAR(merged[0].eyes[0][1].z, mean, 1e-6 * mean);
  // Shard 1 of 3 short of its share: frames [0, 12) are no longer whole.
  ShardSums shortShard({1, 3}, 2, 1, 1);
  shortShard.add(0, frames[1]);
  shortShard.frameDone();
  saveShard(dir, shortShard);
  EXPECT_FALSE(mergeShards(dir, 3, 2, 1, 1));
  fs::remove(shardFile(dir, {0, 4}));
  EXPECT_FALSE(mergeShards(dir, 4, 2, 1, 1));
  EXPECT_EQ(shardCountsIn(dir), (std::vector<int>{1, 3, 4}));
}

// A file from another view size, or cut short, is not loaded: that shard starts over.
TEST(ReferenceShardFiles, MismatchedOrTruncatedFilesAreNotLoaded) {
  const std::string dir = freshDir();
  ShardSums s({0, 2}, 4, 4, 2);
  s.add(1, std::vector<glm::vec3>(16, glm::vec3(1.0f)));
  s.frameDone();
  saveShard(dir, s);
  ASSERT_TRUE(loadShard(dir, {0, 2}, 4, 4, 2));
  EXPECT_EQ(loadShard(dir, {0, 2}, 4, 4, 2)->frames, 1);
  EXPECT_FALSE(loadShard(dir, {0, 2}, 4, 4, 1));
  EXPECT_FALSE(loadShard(dir, {0, 2}, 8, 4, 2));
  EXPECT_FALSE(loadShard(dir, {1, 2}, 4, 4, 2));
  fs::resize_file(shardFile(dir, {0, 2}), fs::file_size(shardFile(dir, {0, 2})) - 1);
  EXPECT_FALSE(loadShard(dir, {0, 2}, 4, 4, 2));
}

}  // namespace
}  // namespace photovr::harness
