// Timewarp: depth-based re-projection by an iterative backward search, for each output
// pixel (Bowles et al. 2012, "Iterative Image Warping"; the same ray-against-depth-buffer
// march as screen-space ray tracing). Two variants from this file:
//   TIMEWARP_PANEL: the headset's whole compositor in one pass (with TIMEWARP_AS_RENDERED
//     the frame as rendered, the search compiled out). For each texel of the
//     rotated panel: its display pixel, the lens table (timewarp_lut.comp) for the
//     tan-angle pose B shows there, the search into pose A's colour + depth, the chromatic
//     channels, exposure, PBR Neutral and sRGB (display_transform.glsl) -> RGBA8.
//   otherwise: pose B's eye buffers (RGBA16F colour, alpha = origin as the grid
//     re-projection's; R32F reversed-Z depth at B), for tests and eye images.
//
// The search. A ray of B through tan-angle t reaches, at inverse A-distance rho (1 / view
// distance in A; 0 at infinity), the A tan-angle r + rho e, where r = proj(R (t, -1)) is the
// rotation-only warp and e = c.xy + c.z r for B's origin c in A's eye space (R, c from
// view_A * inverse(view_B)). So the ray is a segment in A's image, from r (rho = 0) towards
// the near end, and the visible point is the largest rho at which A's depth buffer reaches
// the ray: rho = D(r + rho e). Marched from the nearest to the farthest depth of the 3x3
// tiles around r (timewarp_tiles.comp; on to infinity if the ray left them before
// crossing) in steps of params.y pixels, then refined by the
// secant between the last sample in front and the first behind, and one fixed-point step.
// A crossing where A's depth jumps nearer by more than the ratio threshold passed behind a
// silhouette: a disocclusion, filled with the background texel in front of which the ray
// last was. Pure rotation (c = 0) is one depth fetch; parallax costs one per step.
#include "compositor_shared.h"
#include "display_transform.glsl"

layout(local_size_x = COMP_TW_GROUP, local_size_y = COMP_TW_GROUP) in;
layout(std140, binding = COMP_TW_BINDING) uniform TimewarpBlock { TimewarpUniforms u; };
layout(std430, binding = COMP_TW_STATS) buffer TimewarpStats { uint counts[8]; };
layout(binding = COMP_TW_COLOR) uniform sampler2DArray aColor;  // bilinear, clamp to edge
layout(binding = COMP_TW_DEPTH) uniform sampler2DArray aDepth;
layout(binding = COMP_TW_TILES) uniform sampler2DArray tiles;
#ifdef TIMEWARP_PANEL
layout(binding = COMP_TW_LUT) uniform sampler2D lensTable;
// The groups of output texels the lens shows any pixel of (Timewarp::lensGroups): the rest
// of the panel is cleared to black, not computed.
layout(std430, binding = COMP_TW_GROUPS) readonly buffer LensGroups { uint lensGroups[]; };
layout(rgba8, binding = COMP_TW_I_OUT) writeonly uniform image2D panelOut;
#else
layout(rgba16f, binding = COMP_TW_I_OUT) writeonly uniform image2DArray eyeOut;
layout(r32f, binding = COMP_TW_I_DEPTH) writeonly uniform image2DArray depthOut;
#endif

const int kUncovered = 0, kFilled = 1, kReprojected = 2;

struct Warp {
  vec2 px;      // A pixel coordinate (texel centres at +0.5)
  float rho;    // 1 / A view distance of the point shown
  int origin;   // kUncovered, kFilled, kReprojected
  bool continuous;  // no depth edge within a tile of it: every bilinear tap is on its surface
};

vec2 pixelsPerTan(TimewarpEye w) {
  return vec2(u.size.xy) / vec2(w.aFov.x + w.aFov.y, w.aFov.z + w.aFov.w);
}

// The A pixel coordinate a B tan-angle reaches at infinity (the rotation-only warp), and
// the A-space direction's z (>= 0: the ray leaves A's hemisphere).
vec2 pixelAtInfinity(TimewarpEye w, vec2 tanB, out float qz) {
  vec3 q = mat3(w.bToA) * vec3(tanB, -1.0);
  qz = q.z;
  vec2 r = q.xy / max(-q.z, 1e-6);
  return (r + w.aFov.xw) * pixelsPerTan(w) - w.aPixel.xy;
}

// A's 1 / view distance at pixel coordinate px: its nearest texel, the border's beyond
// the image (as the grid re-projection's border ring), so a ray stepping across the
// border between two samples still meets the surface there.
float rhoAt(vec2 px, int e) {
  ivec2 i = clamp(ivec2(floor(px)), ivec2(0), u.size.xy - 1);
  return max(texelFetch(aDepth, ivec3(i, e), 0).r, 0.0) / u.eye[e].aPixel.z;
}

Warp warpToA(int e, vec2 tanB, out float qz) {
  TimewarpEye w = u.eye[e];
  Warp result = Warp(vec2(0.0), 0.0, kUncovered, false);
  vec2 p0 = pixelAtInfinity(w, tanB, qz);
  if (qz > -1e-6) return result;
  vec3 c = w.bToA[3].xyz;
  vec2 rot = (p0 + w.aPixel.xy) / pixelsPerTan(w) - w.aFov.xw;
  vec2 dp = (c.xy + c.z * rot) * pixelsPerTan(w);  // pixels per unit of rho
  ivec2 tile = clamp(ivec2(floor(p0)) / COMP_TW_TILE, ivec2(0), u.mode.zw - 1);
  vec2 bounds = min(texelFetch(tiles, ivec3(tile, e), 0).rg / w.aPixel.z, w.bPixel.z);
  float rhoLo = bounds.x, rhoHi = bounds.y;
  int n = clamp(int(ceil((rhoHi - rhoLo) * length(dp) / u.params.y)), 1, int(u.params.z));
  float rhoA = rhoHi, dA = rhoAt(p0 + rhoHi * dp, e);  // last sample in front of A's surface
  float rhoB = rhoA, dB = dA;                          // first sample behind it
  if (rhoA > dA) {
    // Between the neighbourhood's nearest and farthest depth; at rho = 0 (behind
    // everything, D >= 0) if the segment left the neighbourhood before crossing.
    for (int i = 1; i <= n + 1; ++i) {
      rhoB = i <= n ? mix(rhoHi, rhoLo, float(i) / float(n)) : 0.0;
      dB = rhoAt(p0 + rhoB * dp, e);
      if (rhoB <= dB) break;
      rhoA = rhoB, dA = dB;
    }
  }
  float rho;
  if (rhoA > dA && dB > dA * (1.0 + u.params.x)) {
    result = Warp(floor(p0 + rhoA * dp) + 0.5, dA, kFilled, false);
  } else {
    float fa = rhoA - dA, fb = rhoB - dB;
    rho = fa > fb ? mix(rhoA, rhoB, fa / (fa - fb)) : dB;
    // Two fixed-point steps onto the surface's own depth there, each taken only while the
    // depth found is within the ratio of the ray's (written out: a loop costs llvmpipe more).
    float d = rhoAt(p0 + rho * dp, e);
    bool onSurface = abs(d - rho) <= rho * u.params.x;
    rho = onSurface ? d : rho;
    d = rhoAt(p0 + rho * dp, e);
    rho = onSurface && abs(d - rho) <= rho * u.params.x ? d : rho;
    result = Warp(p0 + rho * dp, rho, kReprojected, rhoHi <= rhoLo * (1.0 + u.params.x));
  }
  if (any(lessThan(result.px, vec2(0.0))) || any(greaterThan(result.px, vec2(u.size.xy))))
    result.origin = kUncovered;
  return result;
}

// Per-eye counts of the outputs that are not re-projected, one atomic each: they are the
// few (the re-projected count is the rest of the pixels counted, Timewarp::stats). A
// per-group tally behind two barriers cost more than the atomics it saved.
void countOrigin(bool counted, int eye, int origin) {
  if (counted && origin != kReprojected) atomicAdd(counts[eye * 4 + origin], 1u);
}

vec4 bilinear(vec2 px, int e) {
  return texture(aColor, vec3(px / vec2(u.size.xy), float(e)));
}

// The centre of px's 2x2 bilinear footprint, where the gathers sample, so that the
// footprint is floor(px - 0.5)'s whatever the sampler's rounding of a coordinate on a
// texel centre.
vec3 footprintCentre(vec2 px, int e) {
  return vec3((floor(px - 0.5) + 1.0) / vec2(u.size.xy), float(e));
}

// The bilinear weights of the taps around px (textureGather order: (0,1), (1,1), (1,0),
// (0,0) from the lower-left tap) that lie on the surface at 1 / distance rho, renormalised,
// as the grid re-projection's fragment stage does it: taps across a silhouette would bleed
// the other surface's colour. The plain bilinear weights where no tap is on it (sub-pixel
// features).
vec4 surfaceWeights(vec2 px, int e, float rho, out bool allSame) {
  vec4 d = max(textureGather(aDepth, footprintCentre(px, e), 0), 0.0) / u.eye[e].aPixel.z;
  vec4 lo = min(d, vec4(rho)), hi = max(d, vec4(rho));
  bvec4 same = lessThanEqual(hi, lo * (1.0 + u.params.x));
  allSame = all(same);
  vec2 f = fract(px - 0.5);
  vec4 plain = vec4((1.0 - f.x) * f.y, f.x * f.y, f.x * (1.0 - f.y), (1.0 - f.x) * (1.0 - f.y));
  vec4 weights = vec4(same) * plain;
  float sum = dot(weights, vec4(1.0));
  return sum < 1e-6 ? plain : weights / sum;
}

// A's colour at px from the taps 'weights' gives (surfaceWeights).
vec3 surfaceColor(vec2 px, int e, vec4 weights) {
  vec3 uv = footprintCentre(px, e);
  return vec3(dot(weights, textureGather(aColor, uv, 0)), dot(weights, textureGather(aColor, uv, 1)),
              dot(weights, textureGather(aColor, uv, 2)));
}

#ifdef TIMEWARP_PANEL
// The landscape panel texel an output texel shows (gl/panel_output.h panelSourceTexel).
ivec2 sourceTexel(ivec2 o) {
  int w = u.size.z, h = u.size.w, rotation = u.mode.y;
  if (rotation == 90) return ivec2(w - 1 - o.y, o.x);
  if (rotation == 180) return ivec2(w - 1 - o.x, h - 1 - o.y);
  if (rotation == 270) return ivec2(o.y, h - 1 - o.x);
  return o;
}

// Beyond the field the panel shows (the eye buffer's edge, or with overscan the lens's
// field inside it) the panel shows the field's edge, as the distortion pass's clamp-to-edge
// filter does: a tan-angle clamped to it and to B's outermost texel centres. With overscan
// the margin around the field is then there for the turn alone: a head turned within it
// finds rendered texels for every direction shown.
vec2 clampToEyeBuffer(TimewarpEye w, vec2 t) {
  vec2 halfTexel = 0.5 * vec2(w.bFov.x + w.bFov.y, w.bFov.z + w.bFov.w) / vec2(u.size.xy);
  vec2 lo = max(-w.bFov.xw + halfTexel, -w.bField.xw), hi = min(w.bFov.yz - halfTexel, w.bField.yz);
  return clamp(t, lo, hi);
}

void main() {
  uint group = lensGroups[gl_WorkGroupID.x];
  ivec2 o = ivec2(group & 0xffffu, group >> 16u) * COMP_TW_GROUP + ivec2(gl_LocalInvocationID.xy);
  bool inside = all(lessThan(o, imageSize(panelOut)));
  ivec2 p = sourceTexel(o);
  int e = p.x >= u.size.z / 2 ? 1 : 0;
  vec4 lens = inside ? texelFetch(lensTable, p, 0) : vec4(0.0);
  bool sees = lens.z > 0.0;
  vec3 c = vec3(0.0);
  int origin = kUncovered;
  if (sees) {
    TimewarpEye w = u.eye[e];
    vec2 tG = clampToEyeBuffer(w, lens.xy);
    float qz;
#ifdef TIMEWARP_AS_RENDERED
    // Shown as rendered (B = A): the lens's tan-angle straight into A's image, on one
    // surface as far as the taps go (plain bilinear, as the distortion chain).
    Warp g = Warp(pixelAtInfinity(w, tG, qz), 0.0, kReprojected, true);
#else
    Warp g = warpToA(e, tG, qz);
#endif
    origin = g.origin;
    if (origin == kReprojected) {
      // Red and blue: their own rotation-only warp plus green's parallax (which varies
      // over the few pixels between the channels by far less than a pixel).
      vec2 parallax = g.px - pixelAtInfinity(w, tG, qz);
      vec2 pR = pixelAtInfinity(w, clampToEyeBuffer(w, lens.xy * lens.z), qz) + parallax;
      vec2 pB = pixelAtInfinity(w, clampToEyeBuffer(w, lens.xy * lens.w), qz) + parallax;
      c = vec3(bilinear(pR, e).r, bilinear(g.px, e).g, bilinear(pB, e).b);
      if (!g.continuous) {
        bool oneSurface;
        vec4 wt = surfaceWeights(g.px, e, g.rho, oneSurface);
        // At a silhouette: the channels' few pixels apart are not worth a second search.
        if (!oneSurface) c = surfaceColor(g.px, e, wt);
      }
    } else if (origin == kFilled) {
      c = texelFetch(aColor, ivec3(g.px, e), 0).rgb;
    }
  }
  countOrigin(inside && sees, e, origin);
  if (!inside) return;
  c *= u.params.w;
  // NaN, infinite and negative values display as black (core/tonemap.cpp displayColor).
  for (int k = 0; k < 3; ++k)
    if (!(c[k] > 0.0 && c[k] < 3.0e38)) c[k] = 0.0;
  imageStore(panelOut, o, vec4(linearToSrgb(tonemapPbrNeutral(c)), 1.0));
}
#else
void main() {
  ivec3 p = ivec3(gl_GlobalInvocationID);
  bool inside = all(lessThan(p.xy, u.size.xy));
  int e = p.z;
  TimewarpEye w = u.eye[e];
  vec2 tanB = -w.bFov.xw + (vec2(p.xy) + 0.5 + w.bPixel.xy) *
                               vec2(w.bFov.x + w.bFov.y, w.bFov.z + w.bFov.w) / vec2(u.size.xy);
  float qz;
  Warp g = warpToA(e, tanB, qz);
  countOrigin(inside, e, g.origin);
  if (!inside) return;
  vec4 c = vec4(0.0);
  float depth = 0.0;
  if (g.origin != kUncovered) {
    bool oneSurface;
    vec3 surface = surfaceColor(g.px, e, surfaceWeights(g.px, e, g.rho, oneSurface));
    c = g.origin == kReprojected ? vec4(surface, COMP_VALID)
                                 : vec4(texelFetch(aColor, ivec3(g.px, e), 0).rgb, COMP_FILLED);
    // B's reversed-Z: znear_B / (B view distance), the distance from rho along B's ray.
    float cz = w.bToA[3].z;
    depth = w.aPixel.w * g.rho * -qz / (1.0 + g.rho * cz);
  }
  imageStore(eyeOut, p, c);
  imageStore(depthOut, p, vec4(depth));
}
#endif
