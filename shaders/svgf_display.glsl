// The denoiser's outputs for the headset compositor: linear colour (RGBA16F), display
// colour (exposure, Khronos PBR Neutral, sRGB; RGBA8) and reversed-Z depth (R32F), written
// by whichever pass ends the frame (composite, or the resolve after the a-trous filter).
layout(binding = SVGF_C_DEPTH) uniform sampler2DArray cDepth;
layout(rgba16f, binding = SVGF_I_LINEAR) writeonly uniform image2DArray oLinear;
layout(rgba8, binding = SVGF_I_DISPLAY) writeonly uniform image2DArray oDisplay;
layout(r32f, binding = SVGF_I_DEPTH) writeonly uniform image2DArray oDepth;

void writeOutputs(ivec3 p, vec3 linear) {
  vec3 exposed = linear * params.display.x;
  // NaN and negative values display as black, like core/tonemap.cpp displayColor.
  exposed = mix(vec3(0.0), exposed, greaterThan(exposed, vec3(0.0)));
  imageStore(oLinear, p, roundToHalf(vec4(linear, 1.0)));
  imageStore(oDisplay, p, vec4(linearToSrgb(tonemapPbrNeutral(exposed)), 1.0));
  imageStore(oDepth, p, vec4(texelFetch(cDepth, p, 0).r));
}
