// Panel output pass (gl/panel_output.h): exposure, PBR Neutral, sRGB, and the panel's
// rotation. One invocation per OUTPUT texel; the source texel follows panelSourceTexel.
#include "display_transform.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D panel;
layout(rgba8, binding = 0) writeonly uniform image2D outImage;
uniform ivec2 uPanelSize;  // landscape input
uniform int uRotation;     // 0, 90, 180, 270
uniform float uExposure;

ivec2 sourceTexel(ivec2 o) {
  int w = uPanelSize.x, h = uPanelSize.y;
  if (uRotation == 90) return ivec2(w - 1 - o.y, o.x);
  if (uRotation == 180) return ivec2(w - 1 - o.x, h - 1 - o.y);
  if (uRotation == 270) return ivec2(o.y, h - 1 - o.x);
  return o;
}

void main() {
  ivec2 o = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(o, imageSize(outImage)))) return;
  vec3 c = texelFetch(panel, sourceTexel(o), 0).rgb * uExposure;
  // NaN, infinite and negative values display as black, like core/tonemap.cpp displayColor.
  for (int k = 0; k < 3; ++k)
    if (!(c[k] > 0.0 && c[k] < 3.0e38)) c[k] = 0.0;
  imageStore(outImage, o, vec4(linearToSrgb(tonemapPbrNeutral(c)), 1.0));
}
