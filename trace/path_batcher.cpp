#include "trace/path_batcher.h"

#include "trace/path_stages.h"

namespace photovr {

void PathBatcher::beginPixel(size_t pixel) {
  pixels_.push_back({pixel, uint32_t(samples_.size()), 0});
}

void PathBatcher::addHit(const SurfaceHit& hit, const glm::vec3& dir,
                         const SampleCounters& counters, FirstBounce* record,
                         const FirstBounce* reuse, bool ownShadowRay) {
  ++pixels_.back().samples;
  if (reuse) {
    addSample(-1, int32_t(reused_.size()), hit.emission);
    startReusedSample(reused_.emplace_back(), hit, -dir, *reuse, ownShadowRay);
    reusedFrom_.push_back({counters, reuse});
    return;
  }
  addSample(int32_t(paths_.size()), -1, hit.emission);
  startPath(paths_.emplace_back(), hit, -dir, counters, record);
}

// Written in place: a Sample built on the stack and pushed was copied by a 16-byte load of
// its 8- and 4-byte stores, which waited on store forwarding (most of addHit's time).
void PathBatcher::addSample(int32_t start, int32_t finished, const glm::vec3& seen) {
  Sample& s = samples_.emplace_back();
  s.start = start;
  s.finished = finished;
  s.seen = seen;
}

void PathBatcher::addMiss(const glm::vec3& environment) {
  addSample(-1, -1, environment);
  ++pixels_.back().samples;
}

// The reused samples that need no ray are done; the rest become paths from their start.
void PathBatcher::finishReused(const TraceContext& ctx) {
  finished_.resize(reused_.size());
  done_.resize(reused_.size());
  finishReusedSamples(ctx, reused_, finished_, done_, threadScratch());
  for (Sample& s : samples_) {
    if (s.finished < 0 || done_[size_t(s.finished)]) continue;
    const PathState& p = reused_[size_t(s.finished)];
    s.start = int32_t(paths_.size());
    const ReusedFrom& from = reusedFrom_[size_t(s.finished)];
    startPath(paths_.emplace_back(), p.hit, p.wo, from.counters, nullptr, from.reuse);
    paths_.back().ownShadowRay = p.ownShadowRay;
    s.finished = -1;
  }
}

void PathBatcher::flush(const TraceContext& ctx, EyeImage& img, Totals& totals) {
  if (!reused_.empty()) finishReused(ctx);
  results_.resize(paths_.size());
  continuePaths(ctx, std::span<PathState>(paths_), results_, threadScratch());
  for (const Pixel& p : pixels_) {
    PixelEstimate e;
    for (uint32_t j = p.firstSample; j < p.firstSample + p.samples; ++j) {
      const Sample& s = samples_[j];
      if (s.start >= 0)
        addPath(e, s.seen, results_[size_t(s.start)]);
      else if (s.finished >= 0)
        addPath(e, s.seen, finished_[size_t(s.finished)]);
      else
        addMissedRay(e, s.seen);
    }
    storePixel(img, p.index, e);
    totals.rays += e.rays;
    totals.rejected += e.rejected;
    totals.ownBounces += e.ownBounces;
  }
  paths_.clear(), reused_.clear(), reusedFrom_.clear(), samples_.clear(), pixels_.clear();
}

}  // namespace photovr
