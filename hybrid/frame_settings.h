// What one stereo frame asks of the frame pipeline (frame_pipeline.h): typed, parsed once
// by the command line and carried as is.
#pragma once

#include <cstdint>

#include "core/camera.h"
#include "gl/denoiser.h"
#include "hybrid/sample_maps.h"

namespace photovr {

enum class FrameMode { Hybrid, PathTraced };

// Whether a stereo frame's second eye reuses the first eye's paths unless told otherwise
// (--stereo-reuse; measured in docs/MEASUREMENTS.md, "Stereo path reuse").
constexpr bool kStereoReuseDefault = true;
// Whether directional lights' caustics are light-traced unless told otherwise (--caustics;
// trace/caustics.h). On: at equal tracer time their error is lower (spheres, hybrid,
// 120x135: trimmed relMSE 1.4x lower at 32 frames, 2.1x at 128; docs/MEASUREMENTS.md,
// "Light-traced caustics"); a scene without a sun and a smooth caster pays nothing.
constexpr bool kCausticsDefault = true;
const char* frameModeName(FrameMode mode);  // "hybrid", "pt"

// What one frame asks for; may change from frame to frame.
struct FrameSettings {
  FrameMode mode = FrameMode::Hybrid;
  int spp = 1, bounces = 8;
  uint32_t seed = 0;
  SamplerKind sampler = SamplerKind::Sobol;
  SampleMapKind sampleMap = SampleMapKind::Uniform;  // hybrid only
  gl::DenoiseMode denoise = gl::DenoiseMode::Off;
  bool stereoReuse = kStereoReuseDefault;  // the second eye reuses the first's (stereo_reuse.h)
  bool caustics = kCausticsDefault;        // directional lights' caustics light-traced
};

}  // namespace photovr
