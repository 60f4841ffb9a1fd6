// The display side of a frame: a rendered frame's colour + depth (2-layer GL arrays, the
// frame pipeline's StereoFrame::display) re-projected to the newest head pose, through the
// headset's lens, onto its panel (gl/timewarp.h, one pass), and handed to an output
// (display/output.h): the headset's panel, a desktop mirror window, or image files.
//
// The compositor and the lens live together here: the headset's description
// (hmd/headset_description.h) gives the lens, flattened once for GL by hmd::flattenLens.
#pragma once

#include <array>

#include "core/camera.h"
#include "core/lens_params.h"
#include "gl/eye_arrays.h"
#include "gl/panel_output.h"
#include "gl/timewarp.h"
#include "hmd/headset_description.h"

namespace photovr::display {

// The headset's lens on a panel of this pixel count, as the GL passes take it.
LensParams panelLens(const hmd::HeadsetDescription& headset, int panelWidth, int panelHeight);

// Both eyes of a head pose in 'layout' (core/camera.h StereoRig), with the headset's IPD.
std::array<EyeCamera, 2> headEyes(const Pose& head, const StereoLayout& layout, glm::vec2 jitter,
                                  float ipd = kDefaultIpd);
// A tracked pose is relative to the scene's camera: head = base * tracked.
Pose composePose(const Pose& base, const Pose& tracked);

class DisplayOutput;

class Compositor {
 public:
  // Eye buffers laid out as 'eyes' onto a panelWidth x panelHeight panel (the headset's
  // physical panel at that pixel count), the output turned by 'rotation' degrees.
  Compositor(const hmd::HeadsetDescription& headset, const StereoLayout& eyes, int panelWidth,
             int panelHeight, int rotation);

  // 'frame' was rendered with 'from' and is shown at 'to'; reproject = false shows it as
  // rendered (the lens and the display transform only).
  void run(const gl::EyeTextures& frame, const std::array<EyeCamera, 2>& from,
           const std::array<EyeCamera, 2>& to, float exposure, bool reproject = true);
  // The panel image of the last run, to an output.
  void show(DisplayOutput& output, int frame) const;

  gl::Timewarp& timewarp() { return timewarp_; }
  const gl::Timewarp& timewarp() const { return timewarp_; }
  gl::PanelOutput& output() { return output_; }
  const gl::PanelOutput& output() const { return output_; }

 private:
  gl::Timewarp timewarp_;
  gl::PanelOutput output_;
};

}  // namespace photovr::display
