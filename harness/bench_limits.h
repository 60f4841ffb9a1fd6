// Limit figures measured in the same bench run: what raw Embree does with the rays the
// tracer cast (tracer efficiency = photovr rays/s / raw rays/s), and the GL frame's fixed
// cost (an empty G-buffer frame, the read-back alone).
#pragma once

#include <string>

#include "harness/bench_run.h"
#include "gl/context.h"

namespace photovr::harness {

struct TraceLimit {
  std::string scene, mode;  // hybrid: the rays after the rebuilt primary hit; pt: all rays
  uint64_t rays = 0;
  double photovrMraysPerSecond = 0, rawMraysPerSecond = 0;
  double efficiency() const { return photovrMraysPerSecond / rawMraysPerSecond; }
};

// Records the rays of frame 0 (both eyes, 1 spp) in each mode, then times the tracer on
// that frame and bare rtcIntersect1 / rtcOccluded1 on the recorded rays (all threads, best
// of 3 each, back to back so a busy spell slows both).
std::array<TraceLimit, 2> measureTraceLimits(const BenchScene& scene, int width, int height,
                                             gl::Context& context);

struct GlLimit {
  int width = 0, height = 0;
  double emptyFrameMs = 0;  // G-buffer pass of an empty scene, both eyes, to glFinish
  // The read-back alone of what a hybrid frame reads: both eyes' visibility records.
  double readbackMs = 0;     // synchronous
  double pboReadbackMs = 0;  // the same through pixel buffer objects (start + finish)
};

// Best of 5 after one warm-up; the context must be current.
GlLimit measureGlLimits(int width, int height);

}  // namespace photovr::harness
