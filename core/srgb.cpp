// The sRGB transfer function (IEC 61966-2-1), declared in core/image_io.h: kept apart from
// the image files' code so that the tracer's own use of it (texture decoding) needs no
// OpenImageIO (scripts/trace_probe.sh links the tracer without it).
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/image_io.h"

namespace photovr {

float linearToSrgb(float x) {
  if (!(x > 0.0f)) return 0.0f;
  return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

float srgbToLinear(float x) {
  if (!(x > 0.0f)) return 0.0f;
  return x <= 0.04045f ? x / 12.92f : std::pow((x + 0.055f) / 1.055f, 2.4f);
}

uint8_t toSrgb8(float linear) {
  const float e = linearToSrgb(std::clamp(linear, 0.0f, 1.0f));
  return uint8_t(std::lround(e * 255.0f));
}

}  // namespace photovr
