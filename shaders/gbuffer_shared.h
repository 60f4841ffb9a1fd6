// Structures shared by C++ (gl/gbuffer.cpp) and GLSL (gbuffer.vert/.frag): one definition,
// compiled by both (../shared/STYLE.md, 6). Only vec4/mat4/uvec4 members, so the std140
// and std430 layouts equal the C++ layout; gl/gbuffer.cpp static_asserts the sizes.
#ifndef PHOTOVR_GBUFFER_SHARED_H
#define PHOTOVR_GBUFFER_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace photovr::gl::shared {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
#define PHOTOVR_UINT uint32_t
#else
#define PHOTOVR_UINT uint
#endif

// Texture slots of a material, in binding order (texture unit = slot).
#define SLOT_BASE_COLOR 0
#define SLOT_METALLIC_ROUGHNESS 1
#define SLOT_NORMAL 2
#define SLOT_OCCLUSION 3
#define SLOT_EMISSIVE 4
#define SLOT_COUNT 5

#define ALPHA_OPAQUE 0u
#define ALPHA_MASK 1u
#define ALPHA_BLEND 2u  // stochastic coverage: covers with probability alpha

// Background pixels carry this instance id in the visibility record.
#define VISIBILITY_NONE 0xFFFFFFFFu

struct GpuInstance {
  mat4 model;          // object to world
  mat4 previousModel;  // last frame's, for motion vectors
  mat4 normalModel;    // inverse transpose of model (upper 3x3 used)
  uvec4 info;          // x = index in Scene::instances, y = 1 if model mirrors (det < 0)
};

struct GpuMaterial {
  vec4 baseColorFactor;
  vec4 emissive;  // rgb = factor * strength, w = alpha cutoff
  vec4 params;    // metallic, roughness, normal scale, occlusion strength
  uvec4 flags;    // x = alpha mode, y = double sided, z = texture mask (bit = slot),
                  // w = texCoord set mask (bit = slot uses TEXCOORD_1)
  vec4 uvTransform[2 * SLOT_COUNT];  // per slot, rows of the 3x3 uv matrix: (a b c) (d e f)
  vec4 padding[2];  // 256-byte stride: any GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT divides it
};

struct FrameUniforms {
  mat4 viewProjection[2];  // jittered, per eye
  mat4 viewProjectionUnjittered[2];
  mat4 previousViewProjection[2];  // last frame's, unjittered
  vec4 eyePosition[2];             // world
  vec4 rayBase[2];                 // world direction = rayBase + x * rayDx + y * rayDy,
  vec4 rayDx[2];                   // x, y window coordinates of the sample in the eye image
  vec4 rayDy[2];
  vec4 jitter[2];  // xy = this frame's sub-pixel jitter
  vec4 viewport;   // eye width, eye height, 1 / width, 1 / height
};

#ifdef __cplusplus
}  // namespace photovr::gl::shared
#endif
#undef PHOTOVR_UINT
#endif
