#include "hmd/lens.h"

#include <algorithm>
#include <cmath>

namespace photovr::hmd {
namespace {

// Hermite form of dk2.md §6: p0, m0 at t = 0; p1, m1 at t = 1.
double hermite(double p0, double m0, double p1, double m1, double t) {
  const double u = 1.0 - t;
  return (p0 * (1.0 + 2.0 * t) + m0 * t) * u * u + (p1 * (1.0 + 2.0 * u) - m1 * u) * t * t;
}

// Tan-angle radius a channel shows at lens-space radius r.
double tanRadius(const LensDistortion& lens, double r, Channel c) {
  return r * radialScale(lens, r * r, c);
}

// Solves tanRadius(r) = target for r >= 0: Newton steps kept inside a shrinking bracket.
double inverseRadius(const LensDistortion& lens, double target, Channel c) {
  double lo = 0.0, hi = std::max(target, 1e-3);
  while (tanRadius(lens, hi, c) < target && hi < 1e6) hi *= 2.0;
  double r = target / radialScale(lens, 0.0, c);
  for (int i = 0; i < 60; ++i) {
    r = std::clamp(r, lo, hi);
    const double f = tanRadius(lens, r, c) - target;
    (f < 0.0 ? lo : hi) = r;
    if (std::abs(f) < 1e-14 || hi - lo < 1e-15) break;
    const double h = 1e-7 * std::max(r, 1e-3);
    const double slope = (tanRadius(lens, r + h, c) - tanRadius(lens, r - h, c)) / (2.0 * h);
    const double next = slope > 0.0 ? r - f / slope : 0.5 * (lo + hi);
    r = (next > lo && next < hi) ? next : 0.5 * (lo + hi);
  }
  return r;
}

// Through memory: GCC 12 at -O2 can drop the rounding of a plain double(float(x))
// (docs/ARCHITECTURE.md, "Tests: what guards what").
double roundedToFloat(double x) {
  volatile float f = float(x);
  return f;
}

}  // namespace

LensDistortion LensDistortion::dk2Default(double eyeReliefM) {
  LensDistortion l;
  l.k = {1.003, 1.02, 1.042, 1.066, 1.094, 1.126, 1.162, 1.203, 1.25, 1.31, 1.38};
  const std::array<double, 4> ca8 = {-0.0112, -0.015, 0.0187, 0.015};  // 8 mm, dk2.md §6
  const std::array<double, 4> ca18 = {-0.015, -0.02, 0.025, 0.02};     // 18 mm
  const double f = std::clamp((eyeReliefM - 0.008) / 0.010, 0.0, 1.0);
  for (int i = 0; i < 4; ++i) l.chroma[i] = ca8[i] + f * (ca18[i] - ca8[i]);
  l.eyeReliefM = eyeReliefM;
  return l;
}

LensDistortion LensDistortion::fromReport(const LensDistortionReport& r) {
  LensDistortion l;
  for (int i = 0; i < 11; ++i) l.k[i] = r.k[i] / 16384.0;  // 2^14
  l.maxR = r.maxR / 16384.0;
  l.metresPerTanAngle = r.metresPerTanAngle / 524288.0;  // 2^19
  for (int i = 0; i < 4; ++i) l.chroma[i] = (int(r.chroma[i]) - 0x8000) / 524288.0;
  l.eyeReliefM = r.eyeReliefUm * 1e-6;
  return l;
}

PanelGeometry PanelGeometry::fromReport(const DisplayInfoReport& r) {
  return {r.widthUm * 1e-6,          r.heightUm * 1e-6, r.verticalCentreUm * 1e-6,
          r.lensSeparationUm * 1e-6, r.hResolution,     r.vResolution};
}

double catmullRom10(const std::array<double, 11>& k, double x) {
  x = std::max(x, 0.0);
  if (x >= 10.0) return k[10] + (x - 10.0) * (k[10] - k[9]);
  const int s = std::min(int(x), 9);
  const double t = x - s;
  if (s == 0) return hermite(1.0, k[1] - k[0], k[1], 0.5 * (k[2] - k[0]), t);
  if (s == 9) return hermite(k[9], 0.5 * (k[10] - k[8]), k[10], k[10] - k[9], t);
  return hermite(k[s], 0.5 * (k[s + 1] - k[s - 1]), k[s + 1], 0.5 * (k[s + 2] - k[s]), t);
}

double radialScale(const LensDistortion& lens, double rsq, Channel c) {
  const double s = catmullRom10(lens.k, 10.0 * rsq / (lens.maxR * lens.maxR));
  if (c == Channel::Red) return s * (1.0 + lens.chroma[0] + rsq * lens.chroma[1]);
  if (c == Channel::Blue) return s * (1.0 + lens.chroma[2] + rsq * lens.chroma[3]);
  return s;
}

glm::dvec2 lensCentre(const PanelGeometry& p, Eye eye) {
  // Each eye's half is W/2 wide; its lens sits lensSeparation/2 from the panel centre.
  const double x = 1.0 - 2.0 * p.lensSeparationM / p.widthM;
  const double y = 2.0 * p.verticalCentreM / p.heightM - 1.0;
  return {eye == Eye::Left ? x : -x, y};
}

glm::dvec2 screenToLensScale(const LensModel& m) {
  return {0.25 * m.panel.widthM / m.lens.metresPerTanAngle,
          0.5 * m.panel.heightM / m.lens.metresPerTanAngle};
}

LensParams flattenLens(const LensModel& m) {
  // The panel's lengths rounded to float first, the derived values then from them: what
  // gl/ computed itself before this function (centre.x and scale.x are one float ulp
  // apart from the rounded double-length values on the DK2), so no image changed.
  LensModel f = m;
  for (double* v : {&f.lens.metresPerTanAngle, &f.panel.widthM, &f.panel.heightM,
                    &f.panel.verticalCentreM, &f.panel.lensSeparationM})
    *v = roundedToFloat(*v);
  LensParams p;
  for (size_t i = 0; i < p.k.size(); ++i) p.k[i] = float(m.lens.k[i]);
  p.maxR = float(m.lens.maxR);
  p.metresPerTanAngle = float(f.lens.metresPerTanAngle);
  for (size_t i = 0; i < p.chroma.size(); ++i) p.chroma[i] = float(m.lens.chroma[i]);
  p.panelWidthM = float(f.panel.widthM);
  p.panelHeightM = float(f.panel.heightM);
  p.verticalCentreM = float(f.panel.verticalCentreM);
  p.lensSeparationM = float(f.panel.lensSeparationM);
  p.hResolution = m.panel.hResolution;
  p.vResolution = m.panel.vResolution;
  for (Eye e : {Eye::Left, Eye::Right}) p.lensCentre[int(e)] = glm::vec2(lensCentre(f.panel, e));
  p.screenToLensScale = glm::vec2(screenToLensScale(f));
  return p;
}

glm::dvec2 screenToLens(const LensModel& m, Eye eye, const glm::dvec2& screen) {
  return (screen - lensCentre(m.panel, eye)) * screenToLensScale(m);
}

glm::dvec2 screenToTan(const LensModel& m, Eye eye, const glm::dvec2& screen, Channel c) {
  const glm::dvec2 d = screenToLens(m, eye, screen);
  return d * radialScale(m.lens, glm::dot(d, d), c);
}

glm::dvec2 tanToScreen(const LensModel& m, Eye eye, const glm::dvec2& tan, Channel c) {
  const double t = glm::length(tan);
  const glm::dvec2 d = t > 0.0 ? tan * (inverseRadius(m.lens, t, c) / t) : glm::dvec2(0.0);
  return d / screenToLensScale(m) + lensCentre(m.panel, eye);
}

bool lensSees(const LensModel& m, Eye eye, const glm::dvec2& screen) {
  const glm::dvec2 d = screenToLens(m, eye, screen);
  return std::abs(screen.x) <= 1.0 && std::abs(screen.y) <= 1.0 &&
         glm::dot(d, d) <= m.lens.maxR * m.lens.maxR;
}

FovTangents lensFov(const LensModel& m, Eye eye) {
  const glm::dvec2 c = lensCentre(m.panel, eye);
  const glm::dvec2 scale = screenToLensScale(m);
  // Lens-space distance to each screen edge along the axes, capped at the lens limit.
  auto edge = [&](double ndcDistance, double axisScale) {
    const double d = std::min(ndcDistance * axisScale, m.lens.maxR);
    return float(tanRadius(m.lens, d, Channel::Green));
  };
  return {edge(1.0 + c.x, scale.x), edge(1.0 - c.x, scale.x), edge(1.0 - c.y, scale.y),
          edge(1.0 + c.y, scale.y)};
}

glm::dvec2 eyeBufferToTan(const FovTangents& f, int w, int h, const glm::dvec2& px) {
  return {-f.left + px.x * (f.left + f.right) / w, -f.down + px.y * (f.up + f.down) / h};
}

glm::dvec2 tanToEyeBuffer(const FovTangents& f, int w, int h, const glm::dvec2& tan) {
  return {(tan.x + f.left) * w / (f.left + f.right), (tan.y + f.down) * h / (f.up + f.down)};
}

}  // namespace photovr::hmd
