// Texture and material evaluation on the CPU, matching the G-buffer shader: bilinear
// filtering with the sampler's wrap modes, sRGB decoding for colour slots,
// KHR_texture_transform. (No mip-mapping: the tracer samples at a point.)
#pragma once

#include <glm/glm.hpp>

#include "core/scene.h"

namespace photovr {

// Texel fetch with bilinear filtering (or nearest when the texture asks); rgba in [0, 1],
// colour channels decoded from sRGB when 'srgb'.
glm::vec4 sampleTexture(const Texture& texture, glm::vec2 uv, bool srgb);

// sampleSlot for a slot that names a texture ('fallback' if it is out of range).
glm::vec4 sampleSlotTexture(const Scene& scene, const TextureRef& ref, glm::vec2 uv0, glm::vec2 uv1,
                            bool srgb, glm::vec4 fallback);

// The slot's value at the vertex uvs, through its transform; 'fallback' when the slot is
// empty or names no texture. Inline: most slots of a hit are empty (the extensions'), and
// a call for each was ~10 % of surfaceAt's instructions.
inline glm::vec4 sampleSlot(const Scene& scene, const TextureRef& ref, glm::vec2 uv0, glm::vec2 uv1,
                            bool srgb, glm::vec4 fallback) {
  return ref.valid() ? sampleSlotTexture(scene, ref, uv0, uv1, srgb, fallback) : fallback;
}

}  // namespace photovr
