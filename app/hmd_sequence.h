// photovr render --hmd sim FILE | replay FILE | dk2: a headless sequence through the
// headset compositor (hmd_sequence.cpp documents the timing model).
#pragma once

#include "app/commands.h"
#include "app/headset.h"
#include "app/render_request.h"

namespace photovr::app {

struct HmdSequenceOptions {
  double fps = 30.0;        // the renderer's rate: frame k starts at k / fps
  double latencyMs = -1.0;  // render start -> display; < 0: one renderer frame (1000 / fps)
  int rotation = 0;         // panel output rotation (90 = the DK2's native portrait scan)
  int panelWidth = 0, panelHeight = 0;  // 0: the headset's panel (DK2: 1920x1080)
  double overscanDeg = 0.0;  // eye buffers this far beyond the lens's field (StereoLayout)
};

// Removes --fps, --latency-ms, --rotate, --panel WxH and --overscan from 'args'; they are
// accepted only with an --hmd other than none.
HmdSequenceOptions extractHmdSequenceOptions(Args& args, const HmdSpec& hmd);

int renderHmdSequence(RenderRequest& request, const HmdSpec& hmd, HmdSequenceOptions options);

extern const char* const kHmdRenderHelp;

}  // namespace photovr::app
