// The DK2 lens: LibOVR's CatmullRom10 distortion with chromatic terms (dk2.md §6), its
// numerical inverse and the per-eye field of view it implies. Pure math, double precision.
//
// Spaces: 'screen' is one eye's half of the panel in NDC, x right and y up in [-1, 1];
// 'tan' is the tangent of the ray angle through the lens, (x right, y up) in the eye frame,
// the space the eye buffer is rendered in (core/camera.h FovTangents).
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/lens_params.h"
#include "hmd/feature_reports.h"

namespace photovr::hmd {

enum class Channel : int { Red = 0, Green = 1, Blue = 2 };

struct LensDistortion {
  std::array<double, 11> k{};  // Catmull-Rom control values of the radial scale
  double maxR = 1.0;           // lens-space radius the table spans (its last knot)
  double metresPerTanAngle = 0.036;
  std::array<double, 4> chroma{};  // red: 1 + c0 + r^2 c1; blue: 1 + c2 + r^2 c3
  double eyeReliefM = 0.011;

  // dk2.md §6 K and MaxR; chromatic terms interpolated between the 8 and 18 mm sets at
  // the given eye relief (default 11 mm: the LibOVR 0.4 default of §5).
  static LensDistortion dk2Default(double eyeReliefM = 0.011);
  static LensDistortion fromReport(const LensDistortionReport& r);  // dk2.md §2 fixed point
};

// The panel as the display-info report 0x09 describes it (defaults: DK2, dk2.md §2, §5).
struct PanelGeometry {
  double widthM = 0.12576, heightM = 0.07074;
  double verticalCentreM = 0.03537;  // lens axis height above the panel's bottom edge
  double lensSeparationM = 0.0635;
  int hResolution = 1920, vResolution = 1080;  // both eyes, landscape
  static PanelGeometry fromReport(const DisplayInfoReport& r);
  int eyeWidth() const { return hResolution / 2; }
  int eyeHeight() const { return vResolution; }
};

struct LensModel {
  LensDistortion lens = LensDistortion::dk2Default();
  PanelGeometry panel;
};

// Catmull-Rom scale curve (dk2.md §6) at x = 10 rsq / MaxR^2: segment 0 starts at 1,
// segment 9 ends with a one-sided tangent, beyond x = 10 it continues linearly.
double catmullRom10(const std::array<double, 11>& k, double x);
// Radial scale of one channel at lens-space radius^2 (green: the spline alone).
double radialScale(const LensDistortion& lens, double rsq, Channel c);

glm::dvec2 lensCentre(const PanelGeometry& panel, Eye eye);  // screen NDC; left ~(-0.00986, 0)
glm::dvec2 screenToLensScale(const LensModel& m);  // d = (p - c) * this; DK2 (0.8733, 0.9825)

// The model as gl/ takes it (core/lens_params.h): every field in float, with lensCentre
// and screenToLensScale as above, rounded to float.
LensParams flattenLens(const LensModel& m);

// Lens-space offset d of a screen point; |d| <= maxR is inside the calibrated lens.
glm::dvec2 screenToLens(const LensModel& m, Eye eye, const glm::dvec2& screen);
// The lens: which tan-angle a screen point shows, per channel.
glm::dvec2 screenToTan(const LensModel& m, Eye eye, const glm::dvec2& screen,
                       Channel c = Channel::Green);
// Its inverse by safeguarded Newton on the radius (the map is radial and monotonic, which
// decodeLensDistortion enforces); converges to ~1e-12 tan-angle.
glm::dvec2 tanToScreen(const LensModel& m, Eye eye, const glm::dvec2& tan,
                       Channel c = Channel::Green);
// True when the screen point is on this eye's half of the panel and inside the lens's
// calibrated radius (beyond MaxR the spline only extrapolates: the lens's visible limit).
bool lensSees(const LensModel& m, Eye eye, const glm::dvec2& screen);

// The per-eye field: tangents to the screen edges (or the lens limit, if nearer) along the
// lens axes, green channel. DK2 defaults give FovTangents::dk2LeftEye() (dk2.md §5).
FovTangents lensFov(const LensModel& m, Eye eye);

// Eye-buffer mapping (dk2.md §6), y up as in GL: window coordinates (pixels from the lower
// left, core/camera.h EyeCamera) <-> tan-angle.
glm::dvec2 eyeBufferToTan(const FovTangents& fov, int width, int height, const glm::dvec2& px);
glm::dvec2 tanToEyeBuffer(const FovTangents& fov, int width, int height, const glm::dvec2& tan);

}  // namespace photovr::hmd
