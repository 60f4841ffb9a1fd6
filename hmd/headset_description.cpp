#include "hmd/headset_description.h"

namespace photovr::hmd {

HeadsetDescription HeadsetDescription::dk2() {
  HeadsetDescription d;
  d.name = "Oculus Rift DK2";
  d.lens = LensModel{};  // LensDistortion::dk2Default() and PanelGeometry's defaults
  d.ipd = kDefaultIpd;
  d.leftField = FovTangents::dk2LeftEye();
  d.eyeWidth = d.lens.panel.eyeWidth();
  d.eyeHeight = d.lens.panel.eyeHeight();
  d.displayLatency = 0.0209;
  d.scanRotation = 90;
  return d;
}

StereoLayout HeadsetDescription::layout(int fieldWidth, int fieldHeight,
                                        float overscanRadians) const {
  return StereoLayout::forField(leftField, fieldWidth, fieldHeight, overscanRadians);
}

LensModel HeadsetDescription::lensAtPanel(int panelWidth, int panelHeight) const {
  LensModel m = lens;
  m.panel.hResolution = panelWidth;
  m.panel.vResolution = panelHeight;
  return m;
}

}  // namespace photovr::hmd
