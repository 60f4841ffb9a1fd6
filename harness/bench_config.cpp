#include "harness/bench_config.h"

#include <tbb/info.h>

#include "core/camera.h"
#include "hmd/headset_description.h"

namespace photovr::harness {

std::string BenchConfig::shortLabel() const {
  return frameModeName(mode) + std::string("/dn-") + gl::denoiseModeName(denoise) + "/" +
         sampleMapKindName(sampling) + "/" + std::to_string(spp) + "spp/" +
         std::to_string(bounces) + "b/t" + std::to_string(resolvedThreads()) +
         (stereoReuse ? "" : "/sr-off");
}

std::string BenchConfig::label() const {
  return scene + "/" + shortLabel() + "/" + std::to_string(width) + "x" + std::to_string(height);
}

int BenchConfig::resolvedThreads() const {
  return threads > 0 ? threads : tbb::info::default_concurrency();
}

BenchSize scoredSize(bool quick) {
  // quick: a sixty-fourth of a DK2 eye's pixels, 16 frames so pt reaches 16 spp, 128-spp
  // reference (~10 s per scene to render once, then cached).
  return quick ? BenchSize{120, 135, 16, 128} : BenchSize{240, 270, 32, 512};
}

std::vector<BenchConfig> benchMatrix(const std::vector<std::string>& scenes, bool quick,
                                     bool stereoReuse) {
  const BenchSize s = scoredSize(quick);
  std::vector<BenchConfig> out;
  for (const std::string& scene : scenes) {
    BenchConfig base;
    base.scene = scene;
    base.width = s.width, base.height = s.height, base.frames = s.frames;
    base.stereoReuse = stereoReuse;
    auto add = [&](auto&& edit) {
      BenchConfig c = base;
      edit(c);
      out.push_back(c);
    };
    add([](BenchConfig&) {});
    add([](BenchConfig& c) { c.mode = FrameMode::PathTraced; });
    add([](BenchConfig& c) { c.denoise = gl::DenoiseMode::Full; });
    // Lens-matched at 1 spp would trace every visible pixel once (the map's minimum is 1):
    // up to 4 spp shows the redistribution.
    add([](BenchConfig& c) { c.sampling = SampleMapKind::LensMatched, c.spp = 4; });
    // One tracer thread: fewer frames, the curve's slope is known from the rows above.
    add([&](BenchConfig& c) { c.threads = 1, c.frames = quick ? 4 : s.frames; });
    if (!quick) {
      add([](BenchConfig& c) { c.mode = FrameMode::PathTraced, c.threads = 1; });
      add([](BenchConfig& c) {
        c.sampling = SampleMapKind::LensMatched, c.spp = 4, c.denoise = gl::DenoiseMode::Full;
      });
    }
    // The DK2 eye: no reference at this size (128 spp would take ~10 minutes per scene on
    // 2 cores), so timing and peak memory only. Denoised hybrid holds the most memory.
    // Quick: one frame, no warm-up, 1 bounce (memory does not depend on the path length;
    // at 8 bounces the frame took 30-55 s on the shared 2-core machine) and the temporal
    // denoiser only: the denoiser allocates and clears every texture of 'full' in its
    // constructor, so the memory is full's, but full's 5 a-trous passes took ~30 s per DK2
    // frame on llvmpipe (measured).
    for (const FrameMode mode : {FrameMode::Hybrid, FrameMode::PathTraced}) {
      if (quick && mode == FrameMode::PathTraced) continue;
      add([&](BenchConfig& c) {
        c.mode = mode;
        c.denoise = mode == FrameMode::PathTraced ? gl::DenoiseMode::Off
                    : quick                       ? gl::DenoiseMode::Temporal
                                                  : gl::DenoiseMode::Full;
        c.width = hmd::HeadsetDescription::dk2().eyeWidth;
        c.height = hmd::HeadsetDescription::dk2().eyeHeight;
        c.frames = quick ? 1 : 4, c.scored = false, c.bounces = quick ? 1 : c.bounces;
      });
    }
  }
  return out;
}

}  // namespace photovr::harness
