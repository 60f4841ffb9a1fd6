// One iteration of the SVGF edge-avoiding a-trous wavelet filter (§4.3, eqs. 1-2; edge
// stopping §4.4, eqs. 3-5), both eyes in one dispatch. Diffuse and specular are filtered
// side by side with their own variances; specular with its own (tighter) sigma_l and only
// while the step fits the GGX lobe's footprint. With SVGF_COMPOSITE defined (the last
// iteration) the result is also composited, saving a pass that would re-read it; with
// SVGF_SPECULAR_DONE (steps beyond the footprint's cap) specular passes through.
// Where a pixel looks through a smooth mirror or glass, the edge weights are those of the
// surface it shows (primary surface replacement, after Zimmer et al., "Path-space Motion
// Estimation and Decomposition for Robust Animation Filtering", EGSR 2015): that surface's
// instance and normal, from the tracer (NoisyEye::guide). Its depth along the path has no
// screen-space gradient to scale eq. (3) by, so depth is not tested there; a tap on the
// other side of the mirror's silhouette (replaced on one side only), or on another
// instance, weighs 0.
// Reads: colour + variance (RGBA16F x 2), geometry record (RGBA32UI), aux (RGBA16F),
// replaced guides (RGB32F) where the record's SVGF_REPLACED_GUIDE bit says so (compiled in
// with SVGF_GUIDES, for frames that have any: gl/denoiser.h).
// Writes: colour + filtered variance (RGBA16F x 2) [+ the compositing outputs].
#include "svgf_common.glsl"
#ifdef SVGF_COMPOSITE
#include "svgf_composite.glsl"
#endif

layout(local_size_x = SVGF_GROUP, local_size_y = SVGF_GROUP) in;

layout(binding = SVGF_A_DIFFUSE) uniform sampler2DArray aDiffuse;
layout(binding = SVGF_A_SPECULAR) uniform sampler2DArray aSpecular;
layout(binding = SVGF_A_GEOMETRY) uniform usampler2DArray aGeometry;
layout(binding = SVGF_A_AUX) uniform sampler2DArray aAux;
layout(binding = SVGF_A_GUIDE) uniform sampler2DArray aGuide;
layout(rgba16f, binding = SVGF_I_DIFFUSE) writeonly uniform image2DArray oDiffuse;
layout(rgba16f, binding = SVGF_I_SPECULAR) writeonly uniform image2DArray oSpecular;

uniform int uStep;  // 2^iteration (§4.3: the kernel's taps are spread 2^i pixels apart)

// §4.3: 3x3 Gaussian prefilter of the variance before it scales eq. (5), "to reduce
// instability"; kernel (1/4, 1/2, 1/4) per axis, renormalised at the image border.
vec2 prefilteredVariance(ivec3 p) {
  const float k[2] = float[2](0.5, 0.25);
  vec2 sum = vec2(0.0);
  float wsum = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      ivec3 q = p + ivec3(x, y, 0);
      if (!inside(q.xy)) continue;
      float w = k[abs(x)] * k[abs(y)];
      sum += w * vec2(texelFetch(aDiffuse, q, 0).a, texelFetch(aSpecular, q, 0).a);
      wsum += w;
    }
  return sum / wsum;
}

// The edge weight between two pixels with replaced guides: the seen surfaces' normal weight
// (eq. 4) when both show the same instance, else 0. A guide is the normal scaled by
// instance + 1 (its length). Between a replaced pixel and another the weight is 0.
float replacedLog2Weight(vec3 guide, vec3 guideQ) {
  float id = length(guide), idQ = length(guideQ);
  if (abs(id - idQ) >= 0.5) return -1e30;
  return normalLog2Weight(guide / id, guideQ / idQ);
}

void main() {
  ivec3 p = ivec3(gl_GlobalInvocationID);
  if (!inside(p.xy)) return;
  Geometry g = unpackGeometry(texelFetch(aGeometry, p, 0));
  vec4 diffuse = texelFetch(aDiffuse, p, 0);
  vec4 specular = texelFetch(aSpecular, p, 0);
  if (g.instance != SVGF_NO_INSTANCE) {
    vec4 aux = texelFetch(aAux, p, 0);
    vec2 gradient = aux.yz * g.depth;
#ifdef SVGF_GUIDES
    bool replaced = (g.triangle & SVGF_REPLACED_GUIDE) != 0u;
    vec3 guide = replaced ? texelFetch(aGuide, p, 0).rgb : vec3(0.0);
#endif
    // Specular lobe footprint: filter while the step is within 'footprint x GGX alpha'
    // pixels (alpha = roughness^2), at most the cap; mirrors keep their reflections (always
    // >= step 1). gl/denoiser.h gives the measurements behind both.
#ifdef SVGF_SPECULAR_DONE
    // A step past the cap (Denoiser::atrous): no pixel's specular is filtered any more, and
    // the specular taps are compiled out (llvmpipe would pay for them even untaken).
    const bool filterSpecular = false;
#else
    float lobeSteps = min(params.display.z, params.display.y * aux.w * aux.w);
    bool filterSpecular = float(uStep) <= max(1.0, lobeSteps);
#endif
    // §4.4 eq. (5): phi_l = sigma_l sqrt(g3x3(Var)) + epsilon (Falcor's 1e-10).
    vec2 phi = params.edge.zw * sqrt(prefilteredVariance(p)) + 1e-10;
    float ld = luminance(diffuse.rgb), ls = luminance(specular.rgb);
    // B3-spline kernel h = (1, 4, 6, 4, 1) / 16 (§4.3, Dammertz et al. 2010).
    const float h[3] = float[3](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
    vec2 wsum = vec2(h[0] * h[0]);
    vec4 sumD = wsum.x * vec4(diffuse.rgb, wsum.x * diffuse.a);
    vec4 sumS = wsum.y * vec4(specular.rgb, wsum.y * specular.a);
    for (int y = -2; y <= 2; ++y)
      for (int x = -2; x <= 2; ++x) {
        if (x == 0 && y == 0) continue;
        vec2 off = vec2(x, y) * float(uStep);
        ivec3 q = p + ivec3(ivec2(off), 0);
        if (!inside(q.xy)) continue;
        Geometry gq = unpackGeometry(texelFetch(aGeometry, q, 0));
        if (gq.instance == SVGF_NO_INSTANCE) continue;
        float geometry = depthLog2Weight(g.depth, gq.depth, gradient, off) +
                         normalLog2Weight(g.normal, gq.normal);
#ifdef SVGF_GUIDES
        bool replacedQ = (gq.triangle & SVGF_REPLACED_GUIDE) != 0u;
        if (replaced || replacedQ)
          geometry = replaced && replacedQ
                         ? replacedLog2Weight(guide, texelFetch(aGuide, q, 0).rgb)
                         : -1e30;
#endif
        float h2 = h[abs(x)] * h[abs(y)];
        vec4 cd = texelFetch(aDiffuse, q, 0);
        float wd = h2 * exp2(geometry + luminanceLog2Weight(ld, luminance(cd.rgb), phi.x));
        sumD += vec4(wd * cd.rgb, wd * wd * cd.a);  // eq. (2): variance weights squared
        wsum.x += wd;
        if (filterSpecular) {
          vec4 cs = texelFetch(aSpecular, q, 0);
          float ws = h2 * exp2(geometry + luminanceLog2Weight(ls, luminance(cs.rgb), phi.y));
          sumS += vec4(ws * cs.rgb, ws * ws * cs.a);
          wsum.y += ws;
        }
      }
    diffuse = vec4(sumD.rgb / wsum.x, sumD.a / (wsum.x * wsum.x));
    specular = vec4(sumS.rgb / wsum.y, sumS.a / (wsum.y * wsum.y));
  }
  imageStore(oDiffuse, p, roundToHalf(diffuse));
  imageStore(oSpecular, p, roundToHalf(specular));
#ifdef SVGF_COMPOSITE
  composite(p, diffuse.rgb, specular.rgb);
#endif
}
