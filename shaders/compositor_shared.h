// Parameters and bindings shared by C++ (gl/compositor.cpp) and the compositor shaders
// (reproject_*.glsl, distort.comp, timewarp*.comp): one definition compiled by both. Only
// vec4/ivec4/mat4 members, so the std140 layout equals the C++ layout; gl/compositor.cpp
// static_asserts it.
#ifndef PHOTOVR_COMPOSITOR_SHARED_H
#define PHOTOVR_COMPOSITOR_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace photovr::gl::shared {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using mat4 = glm::mat4;
#endif

// Uniform block bindings.
#define COMP_REPROJECT_BINDING 7
#define COMP_DISTORT_BINDING 8

// Texture units of the re-projection pass (2-layer arrays, layer = eye).
#define COMP_R_COLOR 0
#define COMP_R_DEPTH 1

// Distortion pass: eye buffer (sampled, bilinear), panel output, debug tan-angles, footprint.
#define COMP_D_EYE 0
#define COMP_I_PANEL 0
#define COMP_I_TAN_RG 1  // red tan (xy), green tan (zw)
#define COMP_I_TAN_B 2   // blue tan (xy), 1 = the lens sees this pixel (z)
#define COMP_I_FOOTPRINT 3
#define COMP_GROUP 8

// Output alpha of the re-projected colour: where the pixel came from.
#define COMP_VALID 1.0
#define COMP_FILLED 0.5  // disocclusion, filled from the farther side
// (uncovered pixels, outside pose A's frustum, keep the clear value 0)

// Re-projection of one eye from pose A to pose B.
struct ReprojectUniforms {
  mat4 aEyeToBClip;  // projection_B * view_B * inverse(view_A)
  vec4 aFov;         // A's tangents: left, right, up, down
  vec4 aJitter;      // A's jitter (xy), A's znear (z), -
  vec4 params;       // depth ratio threshold, area ratio threshold, fill depth scale, grid step
  ivec4 size;        // A's width, height; B's width, height
};

// The DK2 lens (hmd/lens.h LensModel, flattened) and one eye's buffer and panel half.
struct DistortUniforms {
  vec4 k0;        // Catmull-Rom knots k[0..3]
  vec4 k1;        // k[4..7]
  vec4 k2;        // k[8..10], maxR
  vec4 chroma;    // red: 1 + c0 + r^2 c1; blue: 1 + c2 + r^2 c3
  vec4 lens;      // lens centre (screen NDC, xy), screen-to-lens scale (zw)
  vec4 fov;       // the eye buffer's tangents: left, right, up, down
  ivec4 panel;    // eye half width, height of the panel; x offset of this eye's half; eye
  ivec4 eyeSize;  // eye buffer width, height, 1 = write footprint, -
};

// Timewarp (timewarp*.comp, gl/timewarp.h): bindings.
#define COMP_TW_BINDING 9  // TimewarpUniforms
#define COMP_TW_STATS 10   // SSBO: per eye uncovered, filled outputs (uint x 4 x 2)
#define COMP_TW_GROUPS 11  // SSBO: panel mode's groups, x | y << 16 (in groups) of each
#define COMP_TW_COLOR 0    // A's colour (2-layer array, bilinear sampler)
#define COMP_TW_DEPTH 1    // A's reversed-Z depth (2-layer array)
#define COMP_TW_TILES 2    // dilated tile maxima of A's depth (2-layer array)
#define COMP_TW_LUT 3      // per panel pixel: green tan-angle (xy), red, blue scale (zw)
#define COMP_TW_I_OUT 0    // panel mode: RGBA8 output; eye mode: RGBA16F 2-layer colour
#define COMP_TW_I_DEPTH 1  // eye mode: R32F 2-layer depth at pose B
#define COMP_TW_I_TILES 2  // tile passes: the image written
#define COMP_TW_TILE 16    // tile edge (pixels) of the search bound
#define COMP_TW_GROUP 8

// One eye of the timewarp: pose B's eye space to pose A's, both cameras' tangents.
struct TimewarpEye {
  mat4 bToA;    // view_A * inverse(view_B): rotation (3x3) and B's origin in A (column 3)
  vec4 aFov;    // A's tangents: left, right, up, down
  vec4 aPixel;  // A's jitter (xy), A's znear (z), B's znear (w)
  vec4 bFov;    // B's tangents (eye mode: B's pixel -> tan-angle)
  vec4 bPixel;  // B's jitter (xy, eye mode), the largest usable 1/distance in A (z), -
  vec4 bField;  // the tangents the panel shows at B (panel mode): the lens's field, or B's
};

struct TimewarpUniforms {
  TimewarpEye eye[2];
  vec4 params;  // depth ratio threshold, march step (pixels), max steps, exposure
  ivec4 size;   // eye width, height; panel width, height (landscape, both halves)
  ivec4 mode;   // 0 eye buffers / 1 panel; panel rotation (degrees); tiles x, y
};

#ifdef __cplusplus
}  // namespace photovr::gl::shared
#endif
#endif
