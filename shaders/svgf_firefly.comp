// Firefly suppression before the a-trous filter: a rank-conditioned rank-selection filter
// (Hardie and Barner, IEEE Trans. Image Processing 1994) as NVIDIA's Real-time Denoisers
// apply it to the accumulated signal (NRD, ReLAX's anti-firefly pass): a pixel
// brighter than 'factor' x every neighbour of its surface in the 3x3 around it is scaled
// down to that (gl/denoiser.h says why the factor is 4, not RCRS's 1). Only from above: a
// dark outlier is no firefly, and the filter averages it. A rare bright sample otherwise
// survives the temporal average and is then spread by the filter, whose luminance weights
// it widens through its own variance.
// Reads: accumulated colour + variance (RGBA16F x 2), geometry record. Writes: the same
// with colour clamped, variance unchanged (RGBA16F x 2).
#include "svgf_common.glsl"

layout(local_size_x = SVGF_GROUP, local_size_y = SVGF_GROUP) in;

layout(binding = SVGF_A_DIFFUSE) uniform sampler2DArray aDiffuse;
layout(binding = SVGF_A_SPECULAR) uniform sampler2DArray aSpecular;
layout(binding = SVGF_A_GEOMETRY) uniform usampler2DArray aGeometry;
layout(rgba16f, binding = SVGF_I_DIFFUSE) writeonly uniform image2DArray oDiffuse;
layout(rgba16f, binding = SVGF_I_SPECULAR) writeonly uniform image2DArray oSpecular;

vec4 clampTo(vec4 c, float maxLuminance) {
  float l = luminance(c.rgb);
  return l > maxLuminance ? vec4(c.rgb * (maxLuminance / l), c.a) : c;
}

void main() {
  ivec3 p = ivec3(gl_GlobalInvocationID);
  if (!inside(p.xy)) return;
  uint instance = texelFetch(aGeometry, p, 0).x;
  vec4 diffuse = texelFetch(aDiffuse, p, 0);
  vec4 specular = texelFetch(aSpecular, p, 0);
  if (instance != SVGF_NO_INSTANCE) {
    vec2 hi = vec2(-1.0);  // stays negative without a neighbour on the surface
    for (int y = -1; y <= 1; ++y)
      for (int x = -1; x <= 1; ++x) {
        ivec3 q = p + ivec3(x, y, 0);
        if ((x == 0 && y == 0) || !inside(q.xy) || texelFetch(aGeometry, q, 0).x != instance)
          continue;
        hi = max(hi, vec2(luminance(texelFetch(aDiffuse, q, 0).rgb),
                          luminance(texelFetch(aSpecular, q, 0).rgb)));
      }
    if (hi.x >= 0.0) {
      diffuse = clampTo(diffuse, params.tuning.w * hi.x);
      specular = clampTo(specular, params.tuning.w * hi.y);
    }
  }
  imageStore(oDiffuse, p, roundToHalf(diffuse));
  imageStore(oSpecular, p, roundToHalf(specular));
}
