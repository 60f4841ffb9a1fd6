// The least any depth re-projecting lens pass does, for bench_compositor's floor (never
// shown): per panel texel in the lens's 8x8 groups, the lens table, one depth fetch and the
// three chromatic bilinear taps, stored as they are. No warp arithmetic, no search, no
// silhouette taps, no tone mapping, and the output texel's transposed landscape texel in
// place of the panel rotation's index arithmetic. A compositor that re-projects by depth and
// corrects the lens's chromatic aberration cannot cost less than this on the same machine.
#include "compositor_shared.h"

layout(local_size_x = COMP_TW_GROUP, local_size_y = COMP_TW_GROUP) in;
layout(std140, binding = COMP_TW_BINDING) uniform TimewarpBlock { TimewarpUniforms u; };
layout(binding = COMP_TW_COLOR) uniform sampler2DArray aColor;  // bilinear, clamp to edge
layout(binding = COMP_TW_DEPTH) uniform sampler2DArray aDepth;
layout(binding = COMP_TW_LUT) uniform sampler2D lensTable;
layout(std430, binding = COMP_TW_GROUPS) readonly buffer LensGroups { uint lensGroups[]; };
layout(rgba8, binding = COMP_TW_I_OUT) writeonly uniform image2D panelOut;

void main() {
  uint group = lensGroups[gl_WorkGroupID.x];
  ivec2 o = ivec2(group & 0xffffu, group >> 16u) * COMP_TW_GROUP + ivec2(gl_LocalInvocationID.xy);
  ivec2 p = min(o.yx, u.size.zw - 1);
  int e = p.x >= u.size.z / 2 ? 1 : 0;
  vec4 lens = texelFetch(lensTable, p, 0);
  vec4 fov = u.eye[e].aFov;
  vec2 span = vec2(fov.x + fov.y, fov.z + fov.w);
  vec2 uv = (lens.xy + fov.xw) / span;
  ivec2 texel = clamp(ivec2(uv * vec2(u.size.xy)), ivec2(0), u.size.xy - 1);
  float depth = texelFetch(aDepth, ivec3(texel, e), 0).r;
  uv += depth * 1e-9;  // the depth's use, so that the fetch is kept
  vec2 uvR = (lens.xy * lens.z + fov.xw) / span, uvB = (lens.xy * lens.w + fov.xw) / span;
  vec3 c = vec3(texture(aColor, vec3(uvR, float(e))).r, texture(aColor, vec3(uv, float(e))).g,
                texture(aColor, vec3(uvB, float(e))).b);
  imageStore(panelOut, o, vec4(c, 1.0));
}
