// What the headset commands share (render --hmd, view): the --hmd option, the head-pose
// source it names, the eye cameras of a head pose, and the GL compositor chain that takes
// a rendered frame to the panel (re-projection -> lens distortion -> panel output).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.h"
#include "core/image_io.h"
#include "core/camera.h"
#include "gl/compositor.h"
#include "gl/eye_arrays.h"
#include "gl/timewarp.h"
#include "gl/panel_output.h"
#include "hmd/head_tracker.h"
#include "hmd/lens.h"

namespace photovr::app {

// --hmd dk2 | replay FILE | sim FILE | none.
struct HmdSpec {
  std::string kind = "none";
  std::string file;  // replay, sim
};

// Removes "--hmd KIND [FILE]" from 'args' (the shared Options parser takes one value per
// option) and returns it; UsageError for an unknown kind or a missing file argument.
HmdSpec extractHmdOption(Args& args);

// The pose source 'spec' names. dk2: the headset over hidapi, else nullptr with a one-line
// reason in 'why' (the caller decides whether that is fatal). replay: interactive plays the
// recording through the DK2 driver at its recorded pace (pose(t) on the host clock);
// otherwise the recording is decoded and fused up front and pose(t) is the orientation at
// t seconds of device time after its first sample (deterministic, for headless runs).
// sim: the pose script. Bad files throw InputError naming the file.
std::unique_ptr<hmd::HeadPoseSource> openHeadPoseSource(const HmdSpec& spec, bool interactive,
                                                        std::string* why);

// A tracked pose is relative to the scene's camera: head = base * tracked.
Pose composePose(const Pose& base, const Pose& tracked);

// Both eyes of a head pose in 'layout' (core/camera.h StereoRig).
std::array<EyeCamera, 2> headEyes(const Pose& head, const StereoLayout& layout, glm::vec2 jitter);

// Re-projection of a frame's two eyes to a newer pose, the lens, and the panel output, in
// one pass (gl/timewarp.h).
class HeadsetCompositor {
 public:
  // Eyes laid out as 'eyes' onto a panelWidth x panelHeight panel (the DK2's physical panel
  // at that pixel count), output turned by 'rotation'.
  HeadsetCompositor(const StereoLayout& eyes, int panelWidth, int panelHeight, int rotation);

  // 'colorArray'/'depthArray' (2-layer, linear colour / reversed-Z depth) were rendered
  // with 'from'; shown at 'to'. reproject = false shows the frame as rendered.
  void run(unsigned colorArray, unsigned depthArray, const std::array<EyeCamera, 2>& from,
           const std::array<EyeCamera, 2>& to, float exposure, bool reproject = true);
  // The same from CPU images (rows bottom-up).
  void upload(int eye, const std::vector<glm::vec4>& color, const std::vector<float>& depth);
  void runUploaded(const std::array<EyeCamera, 2>& from, const std::array<EyeCamera, 2>& to,
                   float exposure, bool reproject = true);

  gl::Timewarp& timewarp() { return timewarp_; }
  const gl::Timewarp& timewarp() const { return timewarp_; }
  gl::PanelOutput& output() { return output_; }
  const gl::PanelOutput& output() const { return output_; }

 private:
  gl::Timewarp timewarp_;
  gl::PanelOutput output_;
  gl::EyeArrays uploaded_;
};

// The DK2 lens at a panel's pixel count (hmd::LensModel defaults, dk2.md §2, §6), and both
// eyes' FOVs of a layout, as the compositor uses them.
gl::LensParams dk2PanelLens(int panelWidth, int panelHeight);
std::array<FovTangents, 2> eyeFovs(const StereoLayout& layout);

// GL's bottom-up RGBA8 rows to a top-down RGB image.
Image8 flipToImage(const std::vector<glm::u8vec4>& pixels, int width, int height);

}  // namespace photovr::app
