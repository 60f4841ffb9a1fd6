// The timewarp's search bounds: the farthest and nearest depth (smallest and largest
// reversed-Z) of pose A's eye buffers per COMP_TW_TILE-pixel tile (uPass 0, from the depth
// array), then the extremes of each tile's 3x3 neighbourhood (uPass 1, from pass 0's
// tiles), so a lookup at any pixel bounds every depth within one tile of it. Both eyes in
// one dispatch (z = eye).
#include "compositor_shared.h"

layout(local_size_x = COMP_TW_GROUP, local_size_y = COMP_TW_GROUP) in;
layout(binding = COMP_TW_DEPTH) uniform sampler2DArray source;
layout(rg32f, binding = COMP_TW_I_TILES) writeonly uniform image2DArray tiles;
uniform int uPass;

void main() {
  ivec3 t = ivec3(gl_GlobalInvocationID);
  ivec2 count = imageSize(tiles).xy;
  if (any(greaterThanEqual(t.xy, count))) return;
  vec2 m = vec2(3.0e38, 0.0);  // min, max
  if (uPass == 0) {  // 2x2 texels per gather; the sampler clamps the image's last row/column
    vec2 size = vec2(textureSize(source, 0).xy);
    for (int y = 0; y < COMP_TW_TILE; y += 2)
      for (int x = 0; x < COMP_TW_TILE; x += 2) {
        vec2 uv = (vec2(t.xy * COMP_TW_TILE + ivec2(x, y)) + 1.0) / size;
        vec4 d = textureGather(source, vec3(uv, float(t.z)), 0);
        m = vec2(min(m.x, min(min(d.x, d.y), min(d.z, d.w))),
                 max(m.y, max(max(d.x, d.y), max(d.z, d.w))));
      }
  } else {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        ivec2 n = clamp(t.xy + ivec2(dx, dy), ivec2(0), count - 1);
        vec2 v = texelFetch(source, ivec3(n, t.z), 0).rg;
        m = vec2(min(m.x, v.x), max(m.y, v.y));
      }
  }
  imageStore(tiles, t, vec4(max(m, 0.0), 0.0, 0.0));
}
