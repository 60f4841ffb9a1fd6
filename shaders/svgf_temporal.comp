// SVGF temporal accumulation (§4.1) and variance estimation (§4.2), both eyes in one
// dispatch (z = layer = eye; each layer re-projects into its own history layer).
// Reads: noisy demodulated diffuse/specular (RGB32F), the G-buffer (visibility, normal,
// material, motion, depth), last frame's geometry record, aux, moments and colour history,
// whether the guide is replaced (SVGF_REPLACED_GUIDE).
// Writes: accumulated colour + variance (RGBA16F x 2), this frame's geometry record
// (RGBA32UI), aux (RGBA16F: history length, relative depth gradient, roughness), moments
// (RGBA32F: diffuse mu1 mu2, specular mu1 mu2; 32-bit because mu2 of a bright sample
// overflows half floats).
#include "svgf_common.glsl"

layout(local_size_x = SVGF_GROUP, local_size_y = SVGF_GROUP) in;

layout(binding = SVGF_T_IN_DIFFUSE) uniform sampler2DArray inDiffuse;
layout(binding = SVGF_T_IN_SPECULAR) uniform sampler2DArray inSpecular;
layout(binding = SVGF_T_VISIBILITY) uniform usampler2DArray gVisibility;
layout(binding = SVGF_T_NORMAL) uniform sampler2DArray gNormal;
layout(binding = SVGF_T_MATERIAL) uniform sampler2DArray gMaterial;
layout(binding = SVGF_T_MOTION) uniform sampler2DArray gMotion;
layout(binding = SVGF_T_DEPTH) uniform sampler2DArray gDepth;
layout(binding = SVGF_T_PREV_GEOMETRY) uniform usampler2DArray prevGeometry;
layout(binding = SVGF_T_PREV_AUX) uniform sampler2DArray prevAux;
layout(binding = SVGF_T_PREV_MOMENTS) uniform sampler2DArray prevMoments;
layout(binding = SVGF_T_PREV_DIFFUSE) uniform sampler2DArray prevDiffuse;
layout(binding = SVGF_T_PREV_SPECULAR) uniform sampler2DArray prevSpecular;
layout(binding = SVGF_T_GUIDE) uniform sampler2DArray inGuide;

layout(rgba16f, binding = SVGF_I_DIFFUSE) writeonly uniform image2DArray oDiffuse;
layout(rgba16f, binding = SVGF_I_SPECULAR) writeonly uniform image2DArray oSpecular;
layout(rgba32ui, binding = SVGF_I_GEOMETRY) writeonly uniform uimage2DArray oGeometry;
layout(rgba16f, binding = SVGF_I_AUX) writeonly uniform image2DArray oAux;
layout(rgba32f, binding = SVGF_I_MOMENTS) writeonly uniform image2DArray oMoments;

float depthAt(ivec3 p) { return texelFetch(gDepth, p, 0).r; }

// Screen-space depth gradient divided by the depth (half-float friendly, scale free).
// Per axis the smaller one-sided difference, so a silhouette next to the pixel does not
// count as slope; a missing or background neighbour is never the smaller one.
vec2 relativeDepthGradient(ivec3 p, float d) {
  vec2 g;
  for (int axis = 0; axis < 2; ++axis) {
    ivec3 o = ivec3(axis == 0 ? ivec2(1, 0) : ivec2(0, 1), 0);
    float fwd = inside(p.xy + o.xy) ? depthAt(p + o) - d : 1e30;
    float bwd = inside(p.xy - o.xy) ? d - depthAt(p - o) : 1e30;
    g[axis] = abs(fwd) < abs(bwd) ? fwd : bwd;
    if (abs(g[axis]) > 1e29) g[axis] = 0.0;
  }
  return g / d;
}

// Screen-space variation of the normal, |dn/dx| + |dn/dy| (the fwidth() of Falcor's
// G-buffer, which scales its normal test): per axis the smaller one-sided difference to a
// neighbour of the same instance, so a silhouette does not count as curvature.
float normalWidth(ivec3 p, uint instance, vec3 n) {
  float sum = 0.0;
  for (int axis = 0; axis < 2; ++axis) {
    float best = 1e30;
    for (int side = -1; side <= 1; side += 2) {
      ivec3 q = p + ivec3(axis == 0 ? ivec2(side, 0) : ivec2(0, side), 0);
      if (!inside(q.xy) || texelFetch(gVisibility, q, 0).x != instance) continue;
      best = min(best, distance(n, normalize(texelFetch(gNormal, q, 0).xyz)));
    }
    sum += best < 1e29 ? best : 0.0;
  }
  return sum;
}

struct Current {
  Geometry geo;
  vec2 relGradient;
  float normalWidth;
};

// Back-projection consistency (§4.1: depth, normal and mesh-id tests). Thresholds from
// NVIDIA's reference implementation (Falcor SVGFReproject): reject when the depth change
// exceeds 10x the per-pixel depth slope (plus an epsilon, here relative to the depth),
// or when |n - n_prev| > 16 x (fwidth(n) + 1e-2). The fwidth term matters under the
// per-frame jitter: on a sphere a few pixels wide the normal seen by a pixel moves by
// up to half its screen-space slope between frames (measured: without it the spheres
// scene's spheres never kept any history).
bool consistent(Current c, ivec3 q) {
  if (!inside(q.xy)) return false;
  Geometry g = unpackGeometry(texelFetch(prevGeometry, q, 0));
  if (g.instance != c.geo.instance) return false;
  if (params.reject.w > 0.5 && ((g.triangle ^ c.geo.triangle) & ~SVGF_REPLACED_GUIDE) != 0u)
    return false;
  // Depth as 1 / reversed-Z, i.e. view distance in units of the near plane.
  float z = 1.0 / c.geo.depth, zq = 1.0 / max(g.depth, 1e-30);
  float slope = abs(c.relGradient.x) + abs(c.relGradient.y) + params.reject.y;
  if (abs(z - zq) / (z * slope) > params.reject.x) return false;
  return distance(c.geo.normal, g.normal) <= params.reject.z + params.tuning.x * c.normalWidth;
}

struct History {
  vec3 diffuse, specular;
  vec4 moments;
  float length;
  bool valid;
};

void addTap(inout History h, inout float sum, ivec3 q, float w) {
  h.diffuse += w * texelFetch(prevDiffuse, q, 0).rgb;
  h.specular += w * texelFetch(prevSpecular, q, 0).rgb;
  h.moments += w * texelFetch(prevMoments, q, 0);
  h.length += w * texelFetch(prevAux, q, 0).x;
  sum += w;
}

// Bilinear taps of the previous frame at the back-projected position, each kept only if
// consistent; when none is, any consistent pixel of the 3x3 around it (Falcor's fallback
// for thin features).
History reproject(Current c, ivec3 p) {
  History h = History(vec3(0.0), vec3(0.0), vec4(0.0), 0.0, false);
  if (params.frame.z != 0) return h;
  vec2 prev = vec2(p.xy) + 0.5 + texelFetch(gMotion, p, 0).xy - 0.5;
  ivec2 base = ivec2(floor(prev));
  vec2 f = prev - vec2(base);
  float sum = 0.0;
  for (int i = 0; i < 4; ++i) {
    ivec2 o = ivec2(i & 1, i >> 1);
    float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
    ivec3 q = ivec3(base + o, p.z);
    if (w > 0.0 && consistent(c, q)) addTap(h, sum, q, w);
  }
  if (sum <= 0.0) {
    ivec2 centre = ivec2(floor(prev + 0.5));
    for (int y = -1; y <= 1; ++y)
      for (int x = -1; x <= 1; ++x) {
        ivec3 q = ivec3(centre + ivec2(x, y), p.z);
        if (consistent(c, q)) addTap(h, sum, q, 1.0);
      }
  }
  if (sum <= 0.0) return h;
  h.diffuse /= sum;
  h.specular /= sum;
  h.moments /= sum;
  h.length = floor(h.length / sum + 0.5);
  h.valid = true;
  return h;
}

// Sum of the squared weights of the samples in the moving average after n frames, with
// alpha_k = max(alpha, 1 / k) as in main(): 1 / n while that is the larger, then the
// recursion s_k = (1 - a)^2 s_(k-1) + a^2 (-> alpha / (2 - alpha)).
float sumSquaredWeights(float n) {
  float s = 0.0;
  for (float k = 1.0; k <= n; k += 1.0) {
    float a = max(params.temporal.x, 1.0 / k);
    s = (1.0 - a) * (1.0 - a) * s + a * a;
  }
  return s;
}

vec4 luminanceMoments(vec3 diffuse, vec3 specular) {
  float ld = luminance(diffuse), ls = luminance(specular);
  return vec4(ld, ld * ld, ls, ls * ls);
}

// §4.2: where the history is short, the luminance moments come from a 7x7 bilateral
// neighbourhood of this frame's samples, weighted by depth (eq. 3) and normal (eq. 4).
vec4 spatialMoments(Current c, ivec3 p) {
  vec4 sum = vec4(0.0);
  float wsum = 0.0;
  for (int y = -3; y <= 3; ++y)
    for (int x = -3; x <= 3; ++x) {
      ivec3 q = p + ivec3(x, y, 0);
      if (!inside(q.xy) || texelFetch(gVisibility, q, 0).x == SVGF_NO_INSTANCE) continue;
      vec2 off = vec2(x, y);
      float w = depthWeight(c.geo.depth, depthAt(q), c.relGradient * c.geo.depth, off) *
                normalWeight(c.geo.normal, normalize(texelFetch(gNormal, q, 0).xyz));
      vec3 dq = min(texelFetch(inDiffuse, q, 0).rgb, vec3(SVGF_HALF_MAX));
      vec3 sq = min(texelFetch(inSpecular, q, 0).rgb, vec3(SVGF_HALF_MAX));
      sum += w * luminanceMoments(dq, sq);
      wsum += w;
    }
  return sum / wsum;  // wsum >= 1: the centre has weight 1
}

void main() {
  ivec3 p = ivec3(gl_GlobalInvocationID);
  if (!inside(p.xy)) return;
  uvec4 vis = texelFetch(gVisibility, p, 0);
  float d = depthAt(p);
  vec3 n = normalize(texelFetch(gNormal, p, 0).xyz);
  bool background = vis.x == SVGF_NO_INSTANCE;
  if (background) n = vec3(0.0, 0.0, 1.0);
  uint replaced = texelFetch(inGuide, p, 0).rgb != vec3(0.0) ? SVGF_REPLACED_GUIDE : 0u;
  imageStore(oGeometry, p, uvec4(vis.x, vis.y | replaced, floatBitsToUint(d), packNormal(n)));
  if (background) {
    imageStore(oDiffuse, p, vec4(0.0));
    imageStore(oSpecular, p, vec4(0.0));
    imageStore(oAux, p, vec4(0.0));
    imageStore(oMoments, p, vec4(0.0));
    return;
  }
  Current c = Current(Geometry(vis.x, vis.y, d, n), relativeDepthGradient(p, d),
                      normalWidth(p, vis.x, n));
  vec3 diffuse = min(texelFetch(inDiffuse, p, 0).rgb, vec3(SVGF_HALF_MAX));
  vec3 specular = min(texelFetch(inSpecular, p, 0).rgb, vec3(SVGF_HALF_MAX));
  vec4 moments = luminanceMoments(diffuse, specular);

  History h = reproject(c, p);
  float len = h.valid ? min(h.length + 1.0, params.temporal.z) : 1.0;
  if (h.valid) {
    // §4.1: exponential moving average, alpha = 0.2; max(alpha, 1 / n) makes the first
    // frames a plain mean (Falcor) instead of over-weighting the oldest sample.
    float a = max(params.temporal.x, 1.0 / len);
    float am = max(params.temporal.y, 1.0 / len);
    diffuse = mix(h.diffuse, diffuse, a);
    specular = mix(h.specular, specular, a);
    moments = mix(h.moments, moments, am);
  }
  vec4 m = len < params.temporal.w ? spatialMoments(c, p) : moments;
  // §4.2: Var = mu2 - mu1^2 is the variance of one sample; the colour passed on is the
  // moving average of 'len' of them, whose variance is Var sum w_k^2.
  vec2 variance = max(vec2(0.0), m.yw - m.xz * m.xz) * sumSquaredWeights(len);

  imageStore(oDiffuse, p, roundToHalf(vec4(diffuse, variance.x)));
  imageStore(oSpecular, p, roundToHalf(vec4(specular, variance.y)));
  imageStore(oAux, p, roundToHalf(vec4(len, c.relGradient, texelFetch(gMaterial, p, 0).y)));
  imageStore(oMoments, p, moments);
}
