// Lens distortion pass (dk2.md §6): for each display pixel of one eye's half of the panel,
// the tan-angle each colour channel shows (hmd/lens.cpp screenToTan: LibOVR CatmullRom10
// with chromatic terms, ported to float), a bilinear sample of the eye buffer there, black
// where the lens does not see (hmd/lens.cpp lensSees). Optionally marks every eye-buffer
// texel a bilinear tap reads (the footprint, hmd/lens_maps.h distortionFootprint).
#include "compositor_shared.h"

layout(local_size_x = COMP_GROUP, local_size_y = COMP_GROUP) in;
layout(std140, binding = COMP_DISTORT_BINDING) uniform DistortBlock { DistortUniforms u; };
layout(binding = COMP_D_EYE) uniform sampler2DArray eyeBuffer;
layout(rgba16f, binding = COMP_I_PANEL) writeonly uniform image2D panel;
layout(rgba32f, binding = COMP_I_TAN_RG) writeonly uniform image2D tanRG;
layout(rgba32f, binding = COMP_I_TAN_B) writeonly uniform image2D tanB;
layout(r32ui, binding = COMP_I_FOOTPRINT) writeonly uniform uimage2DArray footprint;

float knot(int i) { return i < 4 ? u.k0[i] : (i < 8 ? u.k1[i - 4] : u.k2[i - 8]); }

float hermite(float p0, float m0, float p1, float m1, float t) {
  float v = 1.0 - t;
  return (p0 * (1.0 + 2.0 * t) + m0 * t) * v * v + (p1 * (1.0 + 2.0 * v) - m1 * v) * t * t;
}

float catmullRom10(float x) {
  x = max(x, 0.0);
  if (x >= 10.0) return knot(10) + (x - 10.0) * (knot(10) - knot(9));
  int s = min(int(x), 9);
  float t = x - float(s);
  if (s == 0) return hermite(1.0, knot(1) - knot(0), knot(1), 0.5 * (knot(2) - knot(0)), t);
  if (s == 9) return hermite(knot(9), 0.5 * (knot(10) - knot(8)), knot(10), knot(10) - knot(9), t);
  return hermite(knot(s), 0.5 * (knot(s + 1) - knot(s - 1)), knot(s + 1),
                 0.5 * (knot(s + 2) - knot(s)), t);
}

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
  vec2 screen = (vec2(p) + 0.5) * 2.0 / vec2(u.panel.xy) - 1.0;
  vec2 d = (screen - u.lens.xy) * u.lens.zw;
  float rsq = dot(d, d), maxR = u.k2.w;
  bool sees = all(lessThanEqual(abs(screen), vec2(1.0))) && rsq <= maxR * maxR;
  float s = catmullRom10(10.0 * rsq / (maxR * maxR));
  vec2 tG = d * s;
  vec2 tR = tG * (1.0 + u.chroma.x + rsq * u.chroma.y);
  vec2 tB = tG * (1.0 + u.chroma.z + rsq * u.chroma.w);
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
