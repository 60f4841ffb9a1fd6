// What `photovr render` was asked to do, parsed and validated once for every mode.
#pragma once

#include <string>

#include "app/commands.h"
#include "core/view.h"
#include "core/progress.h"
#include "core/scene.h"
#include "hybrid/frame_pipeline.h"
#include "hybrid/sample_maps.h"
#include "trace/work_skips.h"

namespace photovr::app {

enum class RenderMode { Hybrid, PathTraced, GBuffer };
const char* renderModeName(RenderMode mode);  // "hybrid", "pt", "gbuffer"

struct RenderRequest {
  std::string sceneSpec;
  RenderMode mode = RenderMode::Hybrid;
  std::string backend;  // empty = egl, falling back to osmesa
  std::string outDir;
  int width = 0, height = 0;
  int spp = 1, bounces = 8, frames = 1;
  uint32_t seed = 0;
  SamplerKind sampler = SamplerKind::Sobol;  // --sampler
  float exposure = 1.0f;
  gl::DenoiseMode denoise = gl::DenoiseMode::Off;
  SampleMapKind sampling = SampleMapKind::Uniform;  // --sampling (hybrid, stereo)
  WorkSkips skips;                         // --no-skip turns skips off (trace/work_skips.h)
  double converge = 0.0;                   // --converge: stop at this estimated relMSE; 0 = off
  bool stereoReuse = kStereoReuseDefault;  // --stereo-reuse
  bool caustics = kCausticsDefault;        // --caustics
  double time = 0.0;                       // --time: the scene time of frame 0 (an animated scene)
  bool play = false;  // --play: frame f at time + f * kAnimationFrameSeconds (motion blur)
  Scene scene;
  View view;
};

RenderRequest parseRenderRequest(const Args& args);  // loads the scene too

// --stereo-reuse on|off (render, view, ab, bench), kStereoReuseDefault when absent.
bool parseStereoReuse(const Options& options);
bool parseCaustics(const Options& options);  // --caustics on|off

// "left"/"right", or "mono" for a mono view's single eye.
inline const char* eyeFolder(const View& v, int eye) {
  return v.stereo ? (eye == 0 ? "left" : "right") : "mono";
}

// The frame settings a request asks for (mode, spp, bounces, seed, sampler, maps, denoiser).
FrameSettings frameSettingsOf(const RenderRequest& request);

int renderGBufferMode(const RenderRequest& request);
// --mode hybrid and --mode pt: frames through the frame pipeline, accumulated (--play:
// posing the request's animated scene at each frame's time).
int renderTracedMode(RenderRequest& request);

extern const char* const kRenderHelp;

}  // namespace photovr::app
