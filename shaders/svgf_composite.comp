// Standalone compositing, for the modes without an a-trous pass to fuse it into:
// 'off' (raw input) and 'temporal' (temporal accumulation output).
#include "svgf_common.glsl"
#include "svgf_composite.glsl"

layout(local_size_x = SVGF_GROUP, local_size_y = SVGF_GROUP) in;
layout(binding = SVGF_A_DIFFUSE) uniform sampler2DArray aDiffuse;
layout(binding = SVGF_A_SPECULAR) uniform sampler2DArray aSpecular;

void main() {
  ivec3 p = ivec3(gl_GlobalInvocationID);
  if (!inside(p.xy)) return;
  composite(p, min(texelFetch(aDiffuse, p, 0).rgb, vec3(SVGF_HALF_MAX)),
            min(texelFetch(aSpecular, p, 0).rgb, vec3(SVGF_HALF_MAX)));
}
