#include "core/tonemap.h"

#include <algorithm>
#include <cmath>

#include "core/image_io.h"

namespace photovr {

glm::vec3 tonemapPbrNeutral(glm::vec3 color) {
  constexpr float kStartCompression = 0.8f - 0.04f;
  constexpr float kDesaturation = 0.15f;
  const float x = std::min(color.r, std::min(color.g, color.b));
  const float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
  color -= offset;
  const float peak = std::max(color.r, std::max(color.g, color.b));
  if (peak < kStartCompression) return color;
  constexpr float d = 1.0f - kStartCompression;
  const float newPeak = 1.0f - d * d / (peak + d - kStartCompression);
  color *= newPeak / peak;
  const float g = 1.0f - 1.0f / (kDesaturation * (peak - newPeak) + 1.0f);
  return glm::mix(color, glm::vec3(newPeak), g);
}

glm::u8vec3 displayColor(const glm::vec3& linear, float exposure) {
  glm::vec3 c = linear * exposure;
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(c[k]) || c[k] < 0.0f) c[k] = 0.0f;
  const glm::vec3 t = tonemapPbrNeutral(c);
  return {toSrgb8(t.r), toSrgb8(t.g), toSrgb8(t.b)};
}

}  // namespace photovr
