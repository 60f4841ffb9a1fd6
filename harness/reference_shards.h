// A reference's frames split into shards that run as independent jobs (GNU parallel, a Slurm
// array, or one process), each writing its own file into the reference's cache folder.
//
// Shard K of N takes frames K, K + N, K + 2N, ... in order. Its file holds the sums of its
// frames' values and of their squares in fixed point (value x 2^32, rounded, in 128-bit
// integers): integer sums do not depend on the order they are added in, so merging any
// complete set of shards gives the reference one unsharded run (shard 0 of 1) gives, bit
// for bit. Files are written atomically after every few frames, so a killed shard re-run
// continues; two jobs of one shard overwrite each other with valid files; jobs of other
// shards never touch each other's.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace photovr::harness {

struct ShardId {
  int index = 0, count = 1;  // shard 'index' of 'count'
};

// "K/N" with 0 <= K < N <= 4096; throws UsageError naming --shard otherwise.
ShardId parseShard(const std::string& text);

// The number of frames [0, totalFrames) that shard 'id' renders.
int framesOfShard(const ShardId& id, int totalFrames);

struct ShardSums {
  ShardId id;
  int width = 0, height = 0, eyes = 0;
  int frames = 0;                           // accumulated: the shard's first 'frames' frames
  std::vector<__int128> sum, sumOfSquares;  // eyes x height x width x 3
  ShardSums() = default;
  ShardSums(ShardId id, int width, int height, int eyes);
  // Adds one frame of eye 'eye' (bottom-up rows of mean radiance); call for every eye, then
  // frameDone().
  void add(int eye, const std::vector<glm::vec3>& values);
  void frameDone() { ++frames; }
};

std::string shardFile(const std::string& directory, const ShardId& id);

// Writes atomically; reads what a matching earlier run left, or nothing (a missing, corrupt
// or mismatched file: the shard starts over).
void saveShard(const std::string& directory, const ShardSums& sums);
std::optional<ShardSums> loadShard(const std::string& directory, const ShardId& id, int width,
                                   int height, int eyes);

struct MergedReference {
  std::vector<std::vector<glm::vec3>> eyes;  // mean per pixel, bottom-up rows
  int frames = 0;
  // The estimated relative MSE of the mean: per pixel, the variance of the frames' values
  // over frames (the mean's variance), over the squared mean (+ relMSE's epsilon), averaged.
  double estimatedRelMse = 0.0;
};

// Sums the N shards of 'count' N as their files stand, when together they hold frames
// [0, T) for some T > 0 (each shard its share of T; MergedReference::frames is T); nothing
// while any of them is missing or its count does not fit the others'.
std::optional<MergedReference> mergeShards(const std::string& directory, int count, int width,
                                           int height, int eyes);

// The shard counts N that have at least one file in 'directory', ascending.
std::vector<int> shardCountsIn(const std::string& directory);

}  // namespace photovr::harness
