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

// The slot's value at the vertex uvs, through its transform; 'fallback' when the slot is
// empty or names no texture.
glm::vec4 sampleSlot(const Scene& scene, const TextureRef& ref, glm::vec2 uv0, glm::vec2 uv1,
                     bool srgb, glm::vec4 fallback);

}  // namespace photovr
