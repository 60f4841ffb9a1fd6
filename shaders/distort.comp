// Lens distortion pass (dk2.md §6): for each display pixel of one eye's half of the panel,
// the tan-angle each colour channel shows (lens_distortion.glsl), a bilinear sample of the
// eye buffer there, black where the lens does not see (hmd/lens.cpp lensSees). Optionally marks every eye-buffer
// texel a bilinear tap reads (the footprint, hmd/lens_maps.h distortionFootprint).
#include "compositor_shared.h"
#include "lens_distortion.glsl"

layout(local_size_x = COMP_GROUP, local_size_y = COMP_GROUP) in;
layout(std140, binding = COMP_DISTORT_BINDING) uniform DistortBlock { DistortUniforms u; };
layout(binding = COMP_D_EYE) uniform sampler2DArray eyeBuffer;
layout(rgba16f, binding = COMP_I_PANEL) writeonly uniform image2D panel;
layout(rgba32f, binding = COMP_I_TAN_RG) writeonly uniform image2D tanRG;
layout(rgba32f, binding = COMP_I_TAN_B) writeonly uniform image2D tanB;
layout(r32ui, binding = COMP_I_FOOTPRINT) writeonly uniform uimage2DArray footprint;

// Bilinear sample of one channel at a tan-angle; marks the taps inside the buffer.
float sampleChannel(vec2 t, int channel, bool mark) {
  ivec2 size = u.eyeSize.xy;
  vec2 px = vec2((t.x + u.fov.x) * float(size.x) / (u.fov.x + u.fov.y),
                 (t.y + u.fov.w) * float(size.y) / (u.fov.z + u.fov.w));
  vec2 p = px - 0.5;
  ivec2 i = ivec2(floor(p));
  vec2 f = p - vec2(i);
  float v[4];
  for (int k = 0; k < 4; ++k) {
    ivec2 tap = i + ivec2(k & 1, k >> 1);
    bool inside = all(greaterThanEqual(tap, ivec2(0))) && all(lessThan(tap, size));
    if (mark && inside) imageStore(footprint, ivec3(tap, u.panel.w), uvec4(1u));
    v[k] = texelFetch(eyeBuffer, ivec3(clamp(tap, ivec2(0), size - 1), u.panel.w), 0)[channel];
  }
  return mix(mix(v[0], v[1], f.x), mix(v[2], v[3], f.x), f.y);
}

// The same sample through the texture unit's bilinear filter (a GL_LINEAR sampler,
// clamp to edge): one fetch instead of four. The debug run keeps the explicit taps above,
// whose footprint the tests compare with hmd::distortionFootprint.
float sampleFiltered(vec2 t, int channel) {
  vec2 uv = vec2((t.x + u.fov.x) / (u.fov.x + u.fov.y), (t.y + u.fov.w) / (u.fov.z + u.fov.w));
  return texture(eyeBuffer, vec3(uv, float(u.panel.w)))[channel];
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, u.panel.xy))) return;
  LensRay ray = lensRay(u, p);
  bool sees = ray.sees;
  vec2 tG = ray.tanG, tR = tG * ray.scaleR, tB = tG * ray.scaleB;
  ivec2 o = p + ivec2(u.panel.z, 0);
  bool mark = u.eyeSize.z != 0;  // debug run: footprint and tan-angles recorded
  if (mark) {
    imageStore(tanRG, o, vec4(tR, tG));
    imageStore(tanB, o, vec4(tB, sees ? 1.0 : 0.0, 0.0));
  }
  vec3 c = vec3(0.0);
  if (sees) {
    if (mark)
      c = vec3(sampleChannel(tR, 0, true), sampleChannel(tG, 1, true), sampleChannel(tB, 2, true));
    else
      c = vec3(sampleFiltered(tR, 0), sampleFiltered(tG, 1), sampleFiltered(tB, 2));
  }
  imageStore(panel, o, vec4(c, 1.0));
}
