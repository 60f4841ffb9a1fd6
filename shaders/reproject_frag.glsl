// Depth re-projection, fragment stage: bilinear colour of pose A at the interpolated A
// texel (perspective-correct, so exact on planes), or the flat background-side fill.
// Bilinear taps on the other side of a depth edge (reversed-Z ratio to the interpolated A
// depth beyond 1 + depth threshold) are dropped, so silhouettes do not bleed colour.
#include "compositor_shared.h"

layout(std140, binding = COMP_REPROJECT_BINDING) uniform ReprojectBlock { ReprojectUniforms u; };
layout(binding = COMP_R_DEPTH) uniform sampler2DArray aDepth;

layout(binding = COMP_R_COLOR) uniform sampler2DArray aColor;
uniform int uEye;

in vec2 vTexel;
in float vDepthA;
flat in vec3 vFill;
flat in float vFillDepth;
layout(location = 0) out vec4 outColor;

vec3 fetch(ivec2 p) {
  ivec2 size = textureSize(aColor, 0).xy;
  return texelFetch(aColor, ivec3(clamp(p, ivec2(0), size - 1), uEye), 0).rgb;
}

// 1 when the tap's depth is on this fragment's surface.
float sameSurface(ivec2 p) {
  ivec2 size = textureSize(aDepth, 0).xy;
  float d = texelFetch(aDepth, ivec3(clamp(p, ivec2(0), size - 1), uEye), 0).r;
  float lo = min(d, vDepthA), hi = max(d, vDepthA);
  return hi <= lo * (1.0 + u.params.x) ? 1.0 : 0.0;
}

void main() {
  if (vFill.z > 0.5) {
    outColor = vec4(fetch(ivec2(vFill.xy)), COMP_FILLED);
    gl_FragDepth = vFillDepth;
    return;
  }
  vec2 p = vTexel - 0.5;
  ivec2 i = ivec2(floor(p));
  vec2 f = p - vec2(i);
  vec3 c = vec3(0.0);
  float wsum = 0.0;
  for (int k = 0; k < 4; ++k) {
    ivec2 o = ivec2(k & 1, k >> 1);
    float w = ((k & 1) != 0 ? f.x : 1.0 - f.x) * ((k >> 1) != 0 ? f.y : 1.0 - f.y);
    w *= sameSurface(i + o);
    c += w * fetch(i + o);
    wsum += w;
  }
  if (wsum > 1e-6) {
    c /= wsum;
  } else {  // no tap on this surface (thin features): plain bilinear
    c = mix(mix(fetch(i), fetch(i + ivec2(1, 0)), f.x),
            mix(fetch(i + ivec2(0, 1)), fetch(i + ivec2(1, 1)), f.x), f.y);
  }
  outColor = vec4(c, COMP_VALID);
  gl_FragDepth = gl_FragCoord.z;
}
