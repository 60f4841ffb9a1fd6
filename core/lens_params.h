// The headset lens as the GPU passes take it: hmd::LensModel flattened to floats, with the
// two values derived from it. One function fills it, hmd::flattenLens (hmd/lens.h, which
// documents each field); gl/ reads it and derives nothing, so the lens math exists once and
// gl/ does not depend on hmd/.
#pragma once

#include <array>

#include <glm/glm.hpp>

namespace photovr {

// Zeros until flattenLens fills it (a panel of width 0 is refused by every pass taking one).
struct LensParams {
  std::array<float, 11> k{};
  float maxR = 0.0f;
  float metresPerTanAngle = 0.0f;
  std::array<float, 4> chroma{};
  float panelWidthM = 0.0f, panelHeightM = 0.0f;
  float verticalCentreM = 0.0f, lensSeparationM = 0.0f;
  int hResolution = 0, vResolution = 0;  // both eyes, landscape
  // Derived (hmd::lensCentre, hmd::screenToLensScale): each eye's lens centre in its half's
  // screen NDC, [0] left, and the screen-to-lens scale, d = (p - c) * this.
  std::array<glm::vec2, 2> lensCentre{};
  glm::vec2 screenToLensScale{0.0f};
};

}  // namespace photovr
