// Parameters and bindings shared by C++ (gl/denoiser.cpp) and the SVGF shaders
// (svgf_*.comp): one definition compiled by both (../shared/STYLE.md, 6). Only vec4/ivec4
// members, so the std140 layout equals the C++ layout; gl/denoiser.cpp static_asserts it.
#ifndef PHOTOVR_DENOISE_SHARED_H
#define PHOTOVR_DENOISE_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace photovr::gl::shared {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
#endif

// Compute work-group edge: 8 x 8 invocations, one layer (eye) per group in z.
#define SVGF_GROUP 8

// Uniform block binding of DenoiseUniforms.
#define SVGF_UNIFORMS_BINDING 6

// Texture units (texelFetch only) of the temporal pass.
#define SVGF_T_IN_DIFFUSE 0
#define SVGF_T_IN_SPECULAR 1
#define SVGF_T_VISIBILITY 2
#define SVGF_T_NORMAL 3
#define SVGF_T_MATERIAL 4
#define SVGF_T_MOTION 5
#define SVGF_T_DEPTH 6
#define SVGF_T_PREV_GEOMETRY 7
#define SVGF_T_PREV_AUX 8
#define SVGF_T_PREV_MOMENTS 9
#define SVGF_T_PREV_DIFFUSE 10
#define SVGF_T_PREV_SPECULAR 11
#define SVGF_T_GUIDE 12
// Texture units of the a-trous and compositing passes.
#define SVGF_A_DIFFUSE 0
#define SVGF_A_SPECULAR 1
#define SVGF_A_GEOMETRY 2
#define SVGF_A_AUX 3
#define SVGF_C_DIFFUSE_ALBEDO 4
#define SVGF_C_SPECULAR_ALBEDO 5
#define SVGF_C_UNFILTERED 6
#define SVGF_C_DEPTH 7
#define SVGF_A_GUIDE 8
// Texture units of the resolve (temporal anti-aliasing) pass; it also writes the outputs.
#define SVGF_R_COLOR 0
#define SVGF_R_HISTORY 1
#define SVGF_R_MOTION 2

// Image units. Temporal: colour, geometry, aux, moments. A-trous: colour. Compositing
// (standalone or fused into the last a-trous iteration) and resolve: outputs; the fused
// composite writes its linear colour for the resolve to SVGF_I_LINEAR.
#define SVGF_I_DIFFUSE 0
#define SVGF_I_SPECULAR 1
#define SVGF_I_GEOMETRY 2
#define SVGF_I_AUX 3
#define SVGF_I_MOMENTS 4
#define SVGF_I_LINEAR 5
#define SVGF_I_DISPLAY 6
#define SVGF_I_DEPTH 7
#define SVGF_I_HISTORY 0  // resolve history

// The geometry record's triangle field carries this bit where the pixel's edge guides are
// replaced (NoisyEye::guide), so the a-trous pass reads the guide texture only there.
#define SVGF_REPLACED_GUIDE 0x80000000u

// Background pixels carry this instance id in the visibility record (gbuffer_shared.h).
#define SVGF_NO_INSTANCE 0xFFFFFFFFu

// Largest finite half float: inputs are clamped to it before they enter RGBA16F history,
// so a firefly cannot become +inf (which would poison the moments and the filter).
#define SVGF_HALF_MAX 65504.0

// Per-frame parameters; gl/denoiser.h documents each with its source.
struct DenoiseUniforms {
  vec4 temporal;  // colour alpha, moments alpha, history cap, frames before temporal variance
  vec4 reject;    // depth reject factor, relative depth epsilon, normal reject distance,
                  // 1 = require the same triangle id
  vec4 edge;      // sigma_z, sigma_n, sigma_l diffuse, sigma_l specular
  vec4 display;   // exposure, specular footprint (steps per unit GGX alpha), its largest
                  // step, -
  vec4 tuning;    // normal reject slope, resolve blend weight, resolve history cap,
                  // firefly factor
  ivec4 frame;    // eye width, eye height, 1 = reset history, -
};

#ifdef __cplusplus
}  // namespace photovr::gl::shared
#endif
#endif
