// Temporal anti-aliasing of the composited frame (the last stage of SVGF's pipeline,
// Schied et al. 2017 §3/fig. 2, after Karis, "High Quality Temporal Supersampling",
// SIGGRAPH 2014 course). SVGF's own history is per surface (rejected on a change of
// instance) and leaves what it does not filter (primary emission, sky, the albedo at
// silhouettes) aliased under the per-frame jitter; this history is per pixel and is kept
// honest by clamping it into the colour range of the pixel's 3x3 neighbourhood in this
// frame (YCoCg, Karis), which also removes trails of anything that moved away.
// Reads: this frame's composite (RGBA16F), last frame's resolve history (RGBA16F: colour,
// sample count), the G-buffer's motion. Writes: the history and the outputs
// (svgf_display.glsl).
#include "svgf_common.glsl"
#include "svgf_display.glsl"

layout(local_size_x = SVGF_GROUP, local_size_y = SVGF_GROUP) in;

layout(binding = SVGF_R_COLOR) uniform sampler2DArray rColor;
layout(binding = SVGF_R_HISTORY) uniform sampler2DArray rHistory;
layout(binding = SVGF_R_MOTION) uniform sampler2DArray rMotion;
layout(rgba16f, binding = SVGF_I_HISTORY) writeonly uniform image2DArray oHistory;

// Karis 2014: the clamp box is tighter (less ghosting) in luma / chroma coordinates.
vec3 toYCoCg(vec3 c) {
  return vec3(dot(c, vec3(0.25, 0.5, 0.25)), dot(c, vec3(0.5, 0.0, -0.5)),
              dot(c, vec3(-0.25, 0.5, -0.25)));
}
vec3 fromYCoCg(vec3 c) {
  float t = c.x - c.z;
  return vec3(t + c.y, c.x + c.z, t - c.y);
}

// Karis 2014: resolve in a range-compressed space, c / (1 + luma), so that a bright
// neighbour (a light, a firefly) weighs in the history kernel and the blend like a
// displayable one; the history is stored compressed, the outputs expanded again.
vec3 compress(vec3 c) { return c / (1.0 + luminance(c)); }
vec3 expand(vec3 c) { return c / max(1.0 - luminance(c), 1.0 / SVGF_HALF_MAX); }

// Catmull-Rom weights of the 4 taps around a sample at fraction t past tap 1.
vec4 catmullRom(float t) {
  return vec4(t * (-0.5 + t * (1.0 - 0.5 * t)), 1.0 + t * t * (-2.5 + 1.5 * t),
              t * (0.5 + t * (2.0 - 1.5 * t)), t * t * (-0.5 + 0.5 * t));
}

// History at a continuous pixel position through a 4x4 Catmull-Rom kernel (Karis 2014:
// bilinear history blurs a little more every frame the camera moves, and an HDR edge such
// as a light's then bleeds into its neighbours for as long as the history lasts). Taps
// outside the eye are dropped and the rest renormalised; alpha = 0 when none is inside.
vec4 history(vec2 pos, int layer) {
  vec2 base = floor(pos - 0.5), f = pos - 0.5 - base;
  vec4 wx = catmullRom(f.x), wy = catmullRom(f.y);
  vec4 sum = vec4(0.0);
  float wsum = 0.0;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      ivec2 q = ivec2(base) + ivec2(x - 1, y - 1);
      float w = wx[x] * wy[y];
      if (w == 0.0 || !inside(q)) continue;
      vec4 h = texelFetch(rHistory, ivec3(q, layer), 0);
      sum += w * vec4(compress(h.rgb), h.a);
      wsum += w;
    }
  return wsum > 0.0 ? vec4(expand(sum.rgb / wsum), sum.a / wsum) : vec4(0.0);
}

void main() {
  ivec3 p = ivec3(gl_GlobalInvocationID);
  if (!inside(p.xy)) return;
  vec3 color = texelFetch(rColor, p, 0).rgb;
  vec3 lo = vec3(1e30), hi = vec3(-1e30);
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      ivec3 q = p + ivec3(x, y, 0);
      if (!inside(q.xy)) continue;
      vec3 c = toYCoCg(texelFetch(rColor, q, 0).rgb);
      lo = min(lo, c);
      hi = max(hi, c);
    }
  vec4 h = params.frame.z != 0
               ? vec4(0.0)
               : history(vec2(p.xy) + 0.5 + texelFetch(rMotion, p, 0).xy, p.z);
  // Sample count in alpha: a plain mean until 1 / n drops below the blend weight.
  float n = min(h.a + 1.0, params.tuning.z);
  float a = max(params.tuning.y, 1.0 / n);
  vec3 clamped = fromYCoCg(clamp(toYCoCg(h.rgb), lo, hi));  // also undoes the kernel's overshoot
  vec3 resolved = mix(clamped, color, a);  // a = 1 without history
  imageStore(oHistory, p, roundToHalf(vec4(resolved, n)));
  writeOutputs(p, resolved);
}
