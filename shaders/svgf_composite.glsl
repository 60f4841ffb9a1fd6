// Compositing (issue 5, item 4): re-modulate the filtered radiance by its albedos (SVGF
// §3: the filter works on demodulated illumination so texture detail is not blurred),
// add what was never filtered (primary emission, sky), then exposure, Khronos PBR Neutral
// and sRGB. Keeps linear colour and depth for the headset compositor.
layout(binding = SVGF_C_DIFFUSE_ALBEDO) uniform sampler2DArray cDiffuseAlbedo;
layout(binding = SVGF_C_SPECULAR_ALBEDO) uniform sampler2DArray cSpecularAlbedo;
layout(binding = SVGF_C_UNFILTERED) uniform sampler2DArray cUnfiltered;
layout(binding = SVGF_C_DEPTH) uniform sampler2DArray cDepth;
layout(rgba16f, binding = SVGF_I_LINEAR) writeonly uniform image2DArray oLinear;
layout(rgba8, binding = SVGF_I_DISPLAY) writeonly uniform image2DArray oDisplay;
layout(r32f, binding = SVGF_I_DEPTH) writeonly uniform image2DArray oDepth;

void composite(ivec3 p, vec3 diffuse, vec3 specular) {
  vec3 linear = diffuse * texelFetch(cDiffuseAlbedo, p, 0).rgb +
                specular * texelFetch(cSpecularAlbedo, p, 0).rgb + texelFetch(cUnfiltered, p, 0).rgb;
  linear = min(linear, vec3(SVGF_HALF_MAX));
  vec3 exposed = linear * params.display.x;
  // NaN and negative values display as black, like core/tonemap.cpp displayColor.
  exposed = mix(vec3(0.0), exposed, greaterThan(exposed, vec3(0.0)));
  imageStore(oLinear, p, roundToHalf(vec4(linear, 1.0)));
  imageStore(oDisplay, p, vec4(linearToSrgb(tonemapPbrNeutral(exposed)), 1.0));
  imageStore(oDepth, p, vec4(texelFetch(cDepth, p, 0).r));
}
