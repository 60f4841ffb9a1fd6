// Per-pixel maps over one eye buffer derived from the lens model: which pixels no lens ray
// reaches (hidden-area mask), how many display pixels each eye-buffer pixel feeds (the
// lens's sample density, from the Jacobian of the distortion), and samples-per-pixel maps
// for the tracer — lens-matched, and the thesis's empirical concentric zones (Algorithm 6).
//
// All maps are width * height, row 0 = the LOWEST row (GL order), index y * width + x.
#pragma once

#include <cstdint>
#include <vector>

#include "hmd/lens.h"

namespace photovr::hmd {

struct EyeBufferSpec {
  Eye eye = Eye::Left;
  FovTangents fov = FovTangents::dk2LeftEye();  // the FOV the eye buffer is rendered with
  int width = kDk2EyeWidth, height = kDk2EyeHeight;
  double overscan = 0.0;  // radians by which 'fov' exceeds the lens's field (StereoLayout)
  FovTangents field = FovTangents::dk2LeftEye();  // with overscan: the field the panel shows
  static EyeBufferSpec of(const StereoLayout& layout, Eye eye) {
    return {eye, layout.fov(eye), layout.width, layout.height, layout.overscan, layout.field(eye)};
  }
};

// 1 = hidden: for every channel the pixel's centre maps to a screen point the lens does
// not show (lensSees), and so does every pixel within 'dilate' pixels (the distortion
// pass's bilinear taps reach one texel beyond the sample point). With overscan the panel
// shows the field alone (gl/timewarp.h setShownField), so what the lens shows within the
// field counts, and every pixel whose direction is within the overscan angle of it: what a
// re-projection to a head turned by up to that angle shows is traced.
std::vector<uint8_t> hiddenAreaMask(const LensModel& m, const EyeBufferSpec& spec, int dilate = 1);

// Reference for the distortion pass: 1 for every eye-buffer texel some display pixel of
// this eye reads (any channel, all four bilinear taps), from display pixel centres the
// lens shows. The GL pass with a counter must agree; hidden pixels must all be 0 here.
std::vector<uint8_t> distortionFootprint(const LensModel& m, const EyeBufferSpec& spec);

// Display pixels per eye-buffer pixel at each pixel centre (green channel): the area of a
// display pixel in tan-angle space is |det d(tan)/d(screen px)|, that of an eye-buffer
// pixel is constant. 0 where hidden. Highest at the lens centre, where one display pixel
// subtends the smallest angle (the barrel pre-distortion stretches the periphery).
// Overscan pixels the lens shows only after a head turn get the lowest density it shows.
std::vector<float> lensDensity(const LensModel& m, const EyeBufferSpec& spec);

// spp = ceil(maxSpp * density / max density), at least 1; 0 for hidden pixels (not traced).
std::vector<uint16_t> lensMatchedSpp(const LensModel& m, const EyeBufferSpec& spec, int maxSpp);

// thesis.md Algorithm 6 (Moschos 2019 §3.3.4), centred on the buffer: nd = d / (0.5 w);
// spp = 1 + ceil(0.125 (1 - nd)(maxSpp - 1)); m = 0.4 w; within m add
// ceil((1 - (d/m)^2)(maxSpp - 1)); clamped to [1, maxSpp] (it has no hidden area).
std::vector<uint16_t> thesisZoneSpp(int width, int height, int maxSpp);

}  // namespace photovr::hmd
