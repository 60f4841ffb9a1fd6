// Pixels' samples gathered into batches for the wavefront tracer (trace/wavefront.h), then
// summed back per pixel in sample order, so that a pixel's estimate is the one a loop of
// continuePath over its samples gives. The pure path tracer and the hybrid both feed it.
// A reused right sample that needs no ray is finished at the flush without a path
// (finishReusedSamples), the batch's such samples together.
#pragma once

#include <cstdint>
#include <vector>

#include "trace/pixel_estimate.h"
#include "trace/wavefront.h"

namespace photovr {

class PathBatcher {
 public:
  // Samples per batch, paths and finished ones: 1024 path states (~190 kB) with their rays
  // stay in L2 while each stage runs over them, and a 16 x 16 tile at 4 spp is one batch.
  static constexpr size_t kBatchPaths = 1024;

  // The samples added next belong to pixel 'pixel' of the image, until the next call.
  void beginPixel(size_t pixel);
  // A sample whose primary ray along 'dir' hit 'hit': its path is continued (stereo reuse:
  // recording its first bounce in 'record', or reusing the left sample 'reuse', finished at
  // the flush without a path where it needs no ray; 'ownShadowRay': it traces its own
  // shadow ray, tracesOwnShadowRay).
  void addHit(const SurfaceHit& hit, const glm::vec3& dir, const SampleCounters& counters,
              FirstBounce* record = nullptr, const FirstBounce* reuse = nullptr,
              bool ownShadowRay = false);
  // A sample whose primary ray left the scene and saw 'environment'.
  void addMiss(const glm::vec3& environment);
  bool full() const { return samples_.size() >= kBatchPaths; }
  // What flushed paths add to an image's counters.
  struct Totals {
    uint64_t rays = 0, rejected = 0;
    uint64_t ownBounces = 0;  // reused right samples that traced an own bounce too
  };
  // Continues every queued path and stores each queued pixel into 'image' (storePixel);
  // adds the paths' counters to 'totals'. Empties the batch.
  void flush(const TraceContext& ctx, EyeImage& image, Totals& totals);

 private:
  void finishReused(const TraceContext& ctx);
  void addSample(int32_t start, int32_t finished, const glm::vec3& seen);

  struct Sample {
    int32_t start = -1;     // index into paths_ and results_ ...
    int32_t finished = -1;  // ... or into reused_ and finished_; both -1: a miss
    glm::vec3 seen{0.0f};   // what the primary ray saw itself: emission, or the environment
  };
  struct Pixel {
    size_t index = 0;
    uint32_t firstSample = 0, samples = 0;
  };
  // The paths to continue, started where they travel (startPath in place: no start and no
  // state copied; spheres' tracer spent 5 % copying them) and their results.
  std::vector<PathState> paths_;
  std::vector<PathResult> results_;
  // Reused right samples, finished at the flush without a path where they need no ray
  // (finishReusedSamples), else continued as paths: their states, the left samples they
  // reuse, their results and whether they were done.
  struct ReusedFrom {
    SampleCounters counters;
    const FirstBounce* reuse = nullptr;
  };
  std::vector<PathState> reused_;
  std::vector<ReusedFrom> reusedFrom_;
  std::vector<PathResult> finished_;
  std::vector<uint8_t> done_;
  std::vector<Sample> samples_;
  std::vector<Pixel> pixels_;
};

}  // namespace photovr
