// Display transform for people: Khronos PBR Neutral and the sRGB encoding, shared by the
// denoiser's composite (through svgf_common.glsl) and the headset's panel output; kept in
// step with core/tonemap.cpp, and tests compare both passes with the CPU version.

// Khronos PBR Neutral (2024 reference GLSL); mirrors core/tonemap.cpp tonemapPbrNeutral.
vec3 tonemapPbrNeutral(vec3 color) {
  const float kStartCompression = 0.8 - 0.04;
  const float kDesaturation = 0.15;
  float x = min(color.r, min(color.g, color.b));
  float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
  color -= offset;
  float peak = max(color.r, max(color.g, color.b));
  if (peak < kStartCompression) return color;
  const float d = 1.0 - kStartCompression;
  float newPeak = 1.0 - d * d / (peak + d - kStartCompression);
  color *= newPeak / peak;
  float g = 1.0 - 1.0 / (kDesaturation * (peak - newPeak) + 1.0);
  return mix(color, vec3(newPeak), g);
}

// IEC 61966-2-1, clamped to [0, 1] first (core/image_io.cpp toSrgb8).
vec3 linearToSrgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}
