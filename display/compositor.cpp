#include "display/compositor.h"

#include "display/output.h"

namespace photovr::display {

LensParams panelLens(const hmd::HeadsetDescription& headset, int panelWidth, int panelHeight) {
  return hmd::flattenLens(headset.lensAtPanel(panelWidth, panelHeight));
}

std::array<EyeCamera, 2> headEyes(const Pose& head, const StereoLayout& layout, glm::vec2 jitter,
                                  float ipd) {
  StereoRig rig;
  rig.head = head;
  rig.ipd = ipd;
  rig.leftFov = layout.leftFov;
  const int w = layout.width, h = layout.height;
  return {rig.eye(Eye::Left, w, h, jitter), rig.eye(Eye::Right, w, h, jitter)};
}

Pose composePose(const Pose& base, const Pose& tracked) {
  Pose p;
  p.position = base.position + base.orientation * tracked.position;
  p.orientation = glm::normalize(base.orientation * tracked.orientation);
  return p;
}

Compositor::Compositor(const hmd::HeadsetDescription& headset, const StereoLayout& eyes,
                       int panelWidth, int panelHeight, int rotation)
    : timewarp_(panelLens(headset, panelWidth, panelHeight), eyes.width, eyes.height,
                {eyes.fov(Eye::Left), eyes.fov(Eye::Right)}),
      output_(panelWidth, panelHeight, rotation) {
  timewarp_.setShownField({eyes.field(Eye::Left), eyes.field(Eye::Right)});
}

void Compositor::run(const gl::EyeTextures& frame, const std::array<EyeCamera, 2>& from,
                     const std::array<EyeCamera, 2>& to, float exposure, bool reproject) {
  if (reproject)
    timewarp_.runPanel(frame.color, frame.depth, from, to, exposure, output_);
  else
    timewarp_.runPanelAsRendered(frame.color, from, exposure, output_);
}

void Compositor::show(DisplayOutput& output, int frame) const {
  output.show(output_, frame);
}

}  // namespace photovr::display
