// Depth re-projection, vertex stage: a grid mesh over pose A's eye buffer displaced by its
// depth and projected to pose B (dk2.md §7, "forward warp with a z-buffered grid mesh").
// Vertices sit at A's pixel sample positions, every params.w-th pixel (the grid step; the
// last row and column always included), plus a ring on the image border so the mesh covers
// A's whole frustum: (N + 2) x (M + 2) vertices for N = ceil(W / step), M = ceil(H / step),
// (N + 1) x (M + 1) quads, drawn without buffers (gl_VertexID = quad * 6 + corner). Step 1
// is one vertex per pixel; a coarser grid is exact on planar surfaces (perspective-correct
// interpolation of A's texel is a homography) and approximates depth edges by its cells.
//
// A triangle whose depths differ by more than the ratio threshold AND whose area grows by
// more than the area threshold in B spans a disocclusion: it is drawn flat with the colour
// of its farthest vertex (background-side fill) at a depth behind that vertex, so real
// surfaces win wherever they exist.
#include "compositor_shared.h"

layout(std140, binding = COMP_REPROJECT_BINDING) uniform ReprojectBlock { ReprojectUniforms u; };
layout(binding = COMP_R_DEPTH) uniform sampler2DArray aDepth;
uniform int uEye;

out vec2 vTexel;                // A texel coordinate (pixels, unjittered) to sample
out float vDepthA;              // A's reversed-Z depth, for depth-aware bilinear taps
flat out vec3 vFill;            // farthest vertex's texel (xy); 1 = disocclusion fill (z)
flat out float vFillDepth;      // window depth of fill fragments

ivec2 sizeA() { return u.size.xy; }
int gridStep() { return int(u.params.w); }
ivec2 gridNodes() { return (sizeA() + gridStep() - 1) / gridStep(); }  // N, M
// The A pixel a grid vertex samples, and its position in A's window coordinates (without
// jitter): the pixel's centre, or the image border for the ring (g = 0 and g > N).
ivec2 gridPixel(ivec2 g) { return clamp((g - 1) * gridStep(), ivec2(0), sizeA() - 1); }
vec2 gridCoord(ivec2 g) {
  vec2 c = vec2(gridPixel(g)) + 0.5;
  c = mix(c, vec2(0.0), lessThan(g, ivec2(1)));
  return mix(c, vec2(sizeA()), greaterThan(g, gridNodes()));
}

// Homogeneous eye-space point of A: (tan, -1, depth / znear) ~ (tan * d, -d, 1), d the view
// distance; reversed-Z depth 0 (infinite distance) is the point at infinity along the ray.
vec4 clipOf(ivec2 g, out float depth) {
  depth = texelFetch(aDepth, ivec3(gridPixel(g), uEye), 0).r;
  vec2 s = gridCoord(g) + u.aJitter.xy;
  vec2 tanA = vec2(-u.aFov.x + s.x * (u.aFov.x + u.aFov.y) / float(sizeA().x),
                   -u.aFov.w + s.y * (u.aFov.z + u.aFov.w) / float(sizeA().y));
  return u.aEyeToBClip * vec4(tanA, -1.0, max(depth, 0.0) / u.aJitter.z);
}

void main() {
  const ivec2 corners[6] = ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0),
                                    ivec2(1, 1), ivec2(0, 1));
  int quad = gl_VertexID / 6, corner = gl_VertexID % 6, first = corner < 3 ? 0 : 3;
  ivec2 q = ivec2(quad % (gridNodes().x + 1), quad / (gridNodes().x + 1));
  ivec2 g[3];
  vec4 c[3];
  float d[3];
  for (int i = 0; i < 3; ++i) {
    g[i] = q + corners[first + i];
    c[i] = clipOf(g[i], d[i]);
  }
  int self = corner - first;
  gl_Position = c[self];
  vTexel = gridCoord(g[self]);
  vDepthA = d[self];

  float dmin = min(d[0], min(d[1], d[2])), dmax = max(d[0], max(d[1], d[2]));
  bool discontinuous = dmax > dmin * (1.0 + u.params.x);
  bool stretched = false;
  if (discontinuous) {
    if (c[0].w <= 0.0 || c[1].w <= 0.0 || c[2].w <= 0.0) {
      stretched = true;
    } else {
      vec2 sb = vec2(u.size.zw) * 0.5;
      vec2 w0 = c[0].xy / c[0].w * sb, w1 = c[1].xy / c[1].w * sb, w2 = c[2].xy / c[2].w * sb;
      vec2 a0 = gridCoord(g[0]), a1 = gridCoord(g[1]), a2 = gridCoord(g[2]);
      float areaB = abs(determinant(mat2(w1 - w0, w2 - w0)));
      float areaA = abs(determinant(mat2(a1 - a0, a2 - a0)));
      stretched = areaB > u.params.y * max(areaA, 1e-6);
    }
  }
  int far = d[0] == dmin ? 0 : (d[1] == dmin ? 1 : 2);
  vFill = vec3(vec2(gridPixel(g[far])), discontinuous && stretched ? 1.0 : 0.0);
  float farDepth = c[far].w > 0.0 ? max(c[far].z / c[far].w, 0.0) : 0.0;
  vFillDepth = farDepth * u.params.z;
}
