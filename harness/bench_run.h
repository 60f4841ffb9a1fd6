// One bench configuration: render its frames, time every stage, score each frame against
// the reference, measure its peak memory.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "harness/bench_config.h"
#include "core/view.h"
#include "core/scene.h"
#include "gl/context.h"

namespace photovr::harness {

struct FrameRecord {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  int frames = 0;  // frames accumulated so far (1-based)
  // Stage wall times of this frame (G-buffer and read-back are hybrid only; denoise is the
  // sum of the denoiser's glFinish-bracketed passes), the frame's wall time, and the wall
  // time of all frames so far (the x axis of error against time).
  double gbufferMs = 0, readbackMs = 0, rebuildMs = 0, traceMs = 0, denoiseMs = 0;
  double frameMs = 0, elapsedMs = 0;
  uint64_t rays = 0;
  double mraysPerSecond = 0;  // tracer rays over tracer time (rebuild + trace, or pt's trace)
  // Of the image shown after this frame (accumulated mean, or the denoiser's output):
  double relMse = kNone, psnr = kNone, ssim = kNone;
};

struct ConfigResult {
  BenchConfig config;
  std::vector<FrameRecord> frames;
  double peakRssMiB = 0;
  uint64_t rejectedSamples = 0;
};

// A scene's view and, for scored configurations, its reference (per eye, rows bottom-up).
struct BenchScene {
  const Scene* scene = nullptr;
  View view;
  std::vector<std::vector<glm::vec3>> reference;
};

// Mean of one per-frame figure over a configuration's frames.
double meanOf(const ConfigResult& result, double FrameRecord::*field);

// The GL context must be current; pt configurations do not use it.
ConfigResult runConfig(const BenchConfig& config, const BenchScene& scene, gl::Context& context);

// Time (ms) the configuration needs to reach relMSE 'error', interpolating its curve in
// log-log; outside the curve, extrapolated from its nearest end as relMSE ~ 1 / time.
// Both are infinite for an empty curve.
double timeToError(const std::vector<FrameRecord>& curve, double error);
// relMSE the configuration reaches after 'ms', interpolated likewise.
double errorAtTime(const std::vector<FrameRecord>& curve, double ms);

}  // namespace photovr::harness
