// Helpers shared by the SVGF passes (Schied et al., "Spatiotemporal Variance-Guided
// Filtering", HPG 2017; section and equation numbers below refer to that paper).
#include "denoise_shared.h"
#include "display_transform.glsl"

layout(std140, binding = SVGF_UNIFORMS_BINDING) uniform DenoiseBlock { DenoiseUniforms params; };

ivec2 eyeSize() { return params.frame.xy; }
bool inside(ivec2 p) { return all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, eyeSize())); }

// Rounds to the nearest half float (ties to even) in float. llvmpipe's float -> half
// conversion on imageStore truncates (measured: a constant image lost one half ulp per
// pass, compounding through the history); a value already on the half grid stores
// exactly under any rounding. Half subnormals (< 6.1e-5) are left to the store.
vec4 roundToHalf(vec4 v) {
  uvec4 b = floatBitsToUint(v);
  b = (b + 0x0FFFu + ((b >> 13) & 1u)) & ~0x1FFFu;
  return uintBitsToFloat(b);
}

// Rec. 709 luminance: the scalar whose moments drive the variance (§4.2).
float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// Octahedral unit-vector encoding (Cigolle et al., JCGT 2014), 2 x 16-bit snorm.
vec2 signNotZero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }
uint packNormal(vec3 n) {
  vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
  if (n.z < 0.0) p = (1.0 - abs(p.yx)) * signNotZero(p);
  return packSnorm2x16(p);
}
vec3 unpackNormal(uint bits) {
  vec2 e = unpackSnorm2x16(bits);
  vec3 v = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (v.z < 0.0) v.xy = (1.0 - abs(v.yx)) * signNotZero(v.xy);
  return normalize(v);
}

// The per-pixel geometry record the temporal pass writes (RGBA32UI): instance, triangle,
// floatBits(reversed-Z depth), octahedral normal. One fetch gives everything the edge
// weights need; the next frame reads it as its "previous G-buffer".
struct Geometry {
  uint instance, triangle;
  float depth;
  vec3 normal;
};
Geometry unpackGeometry(uvec4 g) {
  return Geometry(g.x, g.y, uintBitsToFloat(g.z), unpackNormal(g.w));
}

// The edge-stopping weights of eqs. (3)-(5) as base-2 logarithms: a tap's product of them
// is one exp2 per lobe (the a-trous pass), not an exp or pow per factor.
const float kLog2e = 1.4426950408889634;

// Eq. (3): depth weight, with the depth change predicted by the screen-space gradient
// over the offset as the scale. Reversed-Z depth is affine in screen space on a plane, so
// a plane gives exactly exp(-1 / sigma_z). The epsilon is relative to the depth (depth
// is ~near / distance, so an absolute one would depend on the scene's scale).
float depthLog2Weight(float d, float dq, vec2 gradient, vec2 offset) {
  const float kRelativeEpsilon = 1e-5;  // ~100 float ulps of the depth: planes facing the eye
  float scale = params.edge.x * abs(dot(gradient, offset)) + kRelativeEpsilon * d;
  return -abs(d - dq) * kLog2e / scale;
}

// Eq. (4): normal weight, max(0, n.nq)^sigma_n (2^-12000 = 0 where n.nq <= 0).
float normalLog2Weight(vec3 n, vec3 nq) { return params.edge.y * log2(max(dot(n, nq), 1e-30)); }

// Eq. (5): luminance weight; 'phi' = sigma_l * sqrt(g3x3(Var)) + epsilon.
float luminanceLog2Weight(float l, float lq, float phi) { return -abs(l - lq) * kLog2e / phi; }

float depthWeight(float d, float dq, vec2 gradient, vec2 offset) {
  return exp2(depthLog2Weight(d, dq, gradient, offset));
}
float normalWeight(vec3 n, vec3 nq) { return exp2(normalLog2Weight(n, nq)); }
