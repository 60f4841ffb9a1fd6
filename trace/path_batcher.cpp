#include "trace/path_batcher.h"

namespace photovr {

void PathBatcher::beginPixel(size_t pixel) {
  pixels_.push_back({pixel, uint32_t(samples_.size()), 0});
}

void PathBatcher::addHit(const SurfaceHit& hit, const glm::vec3& dir,
                         const SampleCounters& counters, FirstBounce* record,
                         const FirstBounce* reuse) {
  samples_.push_back({int32_t(starts_.size()), glm::vec3(0.0f)});
  starts_.push_back({hit, -dir, counters, record, reuse});
  ++pixels_.back().samples;
}

void PathBatcher::addMiss(const glm::vec3& environment) {
  samples_.push_back({-1, environment});
  ++pixels_.back().samples;
}

void PathBatcher::flush(const TraceContext& ctx, EyeImage& img, Totals& totals) {
  results_.resize(starts_.size());
  continuePaths(ctx, starts_, results_, threadScratch());
  for (const Pixel& p : pixels_) {
    PixelEstimate e;
    for (uint32_t j = p.firstSample; j < p.firstSample + p.samples; ++j) {
      const Sample& s = samples_[j];
      if (s.start < 0) {
        e.emitted += s.environment;
        ++e.misses;
        continue;
      }
      const PathStart& start = starts_[size_t(s.start)];
      addPath(e, start.hit, results_[size_t(s.start)]);
    }
    storePixel(img, p.index, e);
    totals.rays += e.rays;
    totals.rejected += e.rejected;
    totals.ownBounces += e.ownBounces;
  }
  starts_.clear(), samples_.clear(), pixels_.clear();
}

}  // namespace photovr
