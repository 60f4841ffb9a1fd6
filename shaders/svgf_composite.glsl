// Compositing (issue 5, item 4): re-modulate the filtered radiance by its albedos (SVGF
// §3: the filter works on demodulated illumination so texture detail is not blurred) and
// add what was never filtered (primary emission, sky). With SVGF_RESOLVE_FOLLOWS the
// linear result goes to the resolve pass (svgf_resolve.comp), which writes the outputs;
// otherwise this writes them (svgf_display.glsl).
layout(binding = SVGF_C_DIFFUSE_ALBEDO) uniform sampler2DArray cDiffuseAlbedo;
layout(binding = SVGF_C_SPECULAR_ALBEDO) uniform sampler2DArray cSpecularAlbedo;
layout(binding = SVGF_C_UNFILTERED) uniform sampler2DArray cUnfiltered;
#ifdef SVGF_RESOLVE_FOLLOWS
layout(rgba16f, binding = SVGF_I_LINEAR) writeonly uniform image2DArray oLinear;
#else
#include "svgf_display.glsl"
#endif

void composite(ivec3 p, vec3 diffuse, vec3 specular) {
  vec3 linear = diffuse * texelFetch(cDiffuseAlbedo, p, 0).rgb +
                specular * texelFetch(cSpecularAlbedo, p, 0).rgb + texelFetch(cUnfiltered, p, 0).rgb;
  linear = min(linear, vec3(SVGF_HALF_MAX));
#ifdef SVGF_RESOLVE_FOLLOWS
  imageStore(oLinear, p, roundToHalf(vec4(linear, 1.0)));
#else
  writeOutputs(p, linear);
#endif
}
