// The timewarp's lens table, computed once per lens and panel: for each display pixel of
// one eye's half, the green channel's tan-angle (xy) and the red and blue channels' scale of
// it (zw); z = 0 where the lens does not see the pixel. The same lens as distort.comp.
#include "compositor_shared.h"
#include "lens_distortion.glsl"

layout(local_size_x = COMP_GROUP, local_size_y = COMP_GROUP) in;
layout(std140, binding = COMP_DISTORT_BINDING) uniform DistortBlock { DistortUniforms u; };
layout(rgba32f, binding = COMP_TW_I_OUT) writeonly uniform image2D lut;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, u.panel.xy))) return;
  LensRay ray = lensRay(u, p);
  imageStore(lut, p + ivec2(u.panel.z, 0),
             vec4(ray.tanG, ray.sees ? ray.scaleR : 0.0, ray.scaleB));
}
