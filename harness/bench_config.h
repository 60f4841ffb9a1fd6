// What `photovr bench` measures: one configuration per row, and the matrices it runs.
#pragma once

#include <string>
#include <vector>

#include "gl/denoiser.h"
#include "hybrid/frame_settings.h"

namespace photovr::harness {

struct BenchConfig {
  std::string scene;
  FrameMode mode = FrameMode::Hybrid;
  gl::DenoiseMode denoise = gl::DenoiseMode::Off;
  SampleMapKind sampling = SampleMapKind::Uniform;  // uniform | lens-matched (hybrid only)
  int spp = 1;  // per frame; lens-matched: the most any pixel gets
  int bounces = 8;
  int threads = 0;  // tracer (TBB) threads; 0 = all
  int width = 0, height = 0, frames = 0;
  bool scored = true;  // against the cached converged reference (needs one at this size)
  bool stereoReuse = kStereoReuseDefault;  // --stereo-reuse (the label says "sr-off" when off)

  // A name without spaces or commas (plots and CSV key on it), e.g.
  // "atrium/hybrid/dn-full/uniform/1spp/8b/t2/120x135".
  std::string label() const;
  std::string shortLabel() const;  // the label without scene and size, for plot keys
  int resolvedThreads() const;     // 'threads' with 0 replaced by the machine's count
};

// The quick matrix (under 5 minutes on 2 cores) and the full one; README "Performance"
// lists both. Every scene gets the baseline pair (hybrid and pt, 1 spp, denoiser off,
// uniform, all threads, scored), the denoised hybrid, lens-matched hybrid, the tracer on
// one thread, and the DK2 eye resolution (unscored: timing and peak memory).
// 'stereoReuse': every configuration's (photovr bench --stereo-reuse).
std::vector<BenchConfig> benchMatrix(const std::vector<std::string>& scenes, bool quick,
                                     bool stereoReuse = kStereoReuseDefault);

struct BenchSize {
  int width, height, frames, referenceSpp;
};
BenchSize scoredSize(bool quick);

}  // namespace photovr::harness
