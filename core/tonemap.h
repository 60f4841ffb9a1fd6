// Display transform for images written for people: exposure, Khronos PBR Neutral tone
// mapping, sRGB encoding. Measurements stay linear (EXR).
#pragma once

#include <glm/glm.hpp>

namespace photovr {

// Khronos PBR Neutral (Khronos Group, "PBR Neutral Tone Mapping", 2024, reference GLSL):
// identity below 0.76, a smooth shoulder above, hue-preserving desaturation of highlights.
glm::vec3 tonemapPbrNeutral(glm::vec3 color);

// exposure * color -> PBR Neutral -> sRGB 8-bit.
glm::u8vec3 displayColor(const glm::vec3& linear, float exposure = 1.0f);

}  // namespace photovr
