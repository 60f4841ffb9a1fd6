// Everything photovr needs to know about one headset model, in one place: its lens and
// panel, the field the lens shows, the eye-buffer size it was designed for, the pose
// prediction target and how its panel scans. Another headset is another description: the
// frame pipeline's sample maps, the compositor's lens pass and the commands' defaults all
// read it (hybrid/frame_pipeline.h, display/compositor.h).
#pragma once

#include <string>

#include "core/camera.h"
#include "hmd/lens.h"

namespace photovr::hmd {

struct HeadsetDescription {
  std::string name;
  LensModel lens;  // distortion and panel geometry, at the panel's native pixel count
  float ipd = kDefaultIpd;
  FovTangents leftField;            // the left eye's lens field (the right eye's mirrors it)
  int eyeWidth = 0, eyeHeight = 0;  // native eye buffer: one eye's half of the panel
  // Seconds from present to the middle of scan-out: where poses are predicted to.
  double displayLatency = 0.0;
  int scanRotation = 0;  // degrees the panel is turned from landscape (its scan-out order)

  // Oculus Rift DK2: LibOVR 0.4's defaults at 11 mm eye relief (the lens's CatmullRom10
  // table with the 8/18 mm chromatic terms interpolated), the 1920x1080 panel of its display
  // info report 0x09 (126 x 71 mm, lens separation 63.5 mm), FOV tangents 1.0587 outer,
  // 1.0924 nasal, 1.3293 up and down, 20.9 ms to mid-scan-out (LibOVR 0.3's prediction
  // target), the panel scanning at 90 degrees.
  static HeadsetDescription dk2();

  // The eye buffers for this headset's field at fieldWidth x fieldHeight, widened by the
  // overscan on every side (core/camera.h StereoLayout).
  StereoLayout layout(int fieldWidth, int fieldHeight, float overscanRadians = 0.0f) const;
  // The lens on a panel of this pixel count (a desktop mirror window, a smaller test panel):
  // the same physical panel, sampled more or less finely.
  LensModel lensAtPanel(int panelWidth, int panelHeight) const;
};

}  // namespace photovr::hmd
