// What `photovr render` was asked to do, parsed and validated once for every mode.
#pragma once

#include <string>

#include "app/commands.h"
#include "app/view.h"
#include "core/scene.h"
#include "trace/path_tracer.h"
#include "trace/work_skips.h"

namespace photovr::app {

struct RenderRequest {
  std::string sceneSpec;
  std::string mode;     // gbuffer | pt
  std::string backend;  // empty = egl, falling back to osmesa
  std::string outDir;
  int width = 0, height = 0;
  int spp = 1, bounces = 8, frames = 1;
  uint32_t seed = 0;
  SamplerKind sampler = SamplerKind::Sobol;  // --sampler
  float exposure = 1.0f;
  std::string denoise = "off";       // off | temporal | full (hybrid)
  std::string sampling = "uniform";  // uniform | hidden-area | lens-matched | thesis-zones
  WorkSkips skips;                   // --no-skip turns skips off (trace/work_skips.h)
  double converge = 0.0;             // --converge: stop at this estimated relMSE; 0 = off
  Scene scene;
  View view;
};

RenderRequest parseRenderRequest(const Args& args);  // loads the scene too

// "left"/"right", or "mono" for a mono view's single eye.
inline const char* eyeFolder(const View& v, int eye) {
  return v.stereo ? (eye == 0 ? "left" : "right") : "mono";
}

// The tracer's settings a request asks for (spp, bounces, seed, skips).
TraceSettings traceSettingsOf(const RenderRequest& request);

int renderGBufferMode(const RenderRequest& request);
int renderPathTracedMode(const RenderRequest& request);
int renderHybridMode(const RenderRequest& request);

// Progress on stderr while a long render runs, only when stderr is a terminal.
void reportProgress(double fraction, double raysPerSecond, double secondsLeft);

extern const char* const kRenderHelp;

}  // namespace photovr::app
