// Stereo-instanced G-buffer, fragment stage. The visibility record's barycentrics are not
// interpolated: they come from intersecting the pixel's own jittered primary ray with the
// triangle (Moller-Trumbore, world space, float), the same computation a ray tracer does,
// so the hit point rebuilds to float precision (../shared/DESIGN.md, "Rebuilding a hit").
#include "gbuffer_common.glsl"

in vec3 vNormal;
in vec4 vTangent;
in vec2 vUv0;
in vec2 vUv1;
in vec4 vClip;
in vec4 vPreviousClip;
flat in uint vEye;
flat in uint vInstance;

layout(binding = SLOT_BASE_COLOR) uniform sampler2D uBaseColor;
layout(binding = SLOT_METALLIC_ROUGHNESS) uniform sampler2D uMetallicRoughness;
layout(binding = SLOT_NORMAL) uniform sampler2D uNormal;
layout(binding = SLOT_OCCLUSION) uniform sampler2D uOcclusion;
layout(binding = SLOT_EMISSIVE) uniform sampler2D uEmissive;

layout(location = 0) out uvec4 outVisibility;  // instance, triangle, b1 bits, b2 bits
layout(location = 1) out vec4 outNormal;       // world shading normal, w = 1
layout(location = 2) out vec4 outBaseColor;    // linear rgb, a = occlusion
layout(location = 3) out vec4 outMaterial;     // metallic, roughness, 0, 0
layout(location = 4) out vec4 outEmission;     // linear radiance
layout(location = 5) out vec2 outMotion;       // pixels to add to reach last frame's position

vec3 vertexPosition(uint i) {
  return vec3(meshPositions[3u * i], meshPositions[3u * i + 1u], meshPositions[3u * i + 2u]);
}

// Barycentrics (b1, b2) of the world-space hit of the pixel's ray.
vec2 rayBarycentrics(GpuInstance inst, uint triangle) {
  mat4 m = inst.model;
  vec3 p0 = (m * vec4(vertexPosition(meshIndices[3u * triangle]), 1.0)).xyz;
  vec3 p1 = (m * vec4(vertexPosition(meshIndices[3u * triangle + 1u]), 1.0)).xyz;
  vec3 p2 = (m * vec4(vertexPosition(meshIndices[3u * triangle + 2u]), 1.0)).xyz;
  vec2 pixel = gl_FragCoord.xy + frame.jitter[vEye].xy;
#ifndef PHOTOVR_LAYERED
  pixel.x -= float(vEye) * frame.viewport.x;
#endif
  vec3 dir = frame.rayBase[vEye].xyz + pixel.x * frame.rayDx[vEye].xyz +
             pixel.y * frame.rayDy[vEye].xyz;
  vec3 e1 = p1 - p0, e2 = p2 - p0;
  vec3 pv = cross(dir, e2);
  float det = dot(e1, pv);
  vec3 tv = frame.eyePosition[vEye].xyz - p0;
  float inv = 1.0 / det;
  float b1 = dot(tv, pv) * inv;
  float b2 = dot(dir, cross(tv, e1)) * inv;
  return vec2(b1, b2);
}

bool hasSlot(GpuMaterial mat, int slot) { return (mat.flags.z & (1u << slot)) != 0u; }

// The slot's texture coordinate set, through its KHR_texture_transform.
vec2 slotUv(GpuMaterial mat, int slot) {
  vec2 uv = ((mat.flags.w & (1u << slot)) != 0u) ? vUv1 : vUv0;
  vec3 t = vec3(uv, 1.0);
  return vec2(dot(mat.uvTransform[2 * slot].xyz, t), dot(mat.uvTransform[2 * slot + 1].xyz, t));
}

// Sampled unconditionally, selected after: implicit derivatives are undefined inside
// non-uniform control flow.
#define SAMPLE_SLOT(mat, slot, sampler, fallback) \
  mix((fallback), texture(sampler, slotUv(mat, slot)), bvec4(hasSlot(mat, slot)))

vec3 shadingNormal(GpuMaterial mat, bool frontFacing) {
  vec3 n = normalize(vNormal);
  vec4 t = vTangent;
  if ((mat.flags.z & (1u << SLOT_NORMAL)) != 0u && dot(t.xyz, t.xyz) > 0.0) {
    vec3 tangent = normalize(t.xyz - n * dot(n, t.xyz));
    vec3 bitangent = cross(n, tangent) * (t.w < 0.0 ? -1.0 : 1.0);
    vec3 tn = SAMPLE_SLOT(mat, SLOT_NORMAL, uNormal, vec4(0.5, 0.5, 1.0, 1.0)).xyz * 2.0 - 1.0;
    tn.xy *= mat.params.z;
    n = normalize(tn.x * tangent + tn.y * bitangent + tn.z * n);
  }
  // glTF §3.9.6: back faces of double-sided materials shade with the flipped normal.
  return frontFacing ? n : -n;
}

// trace/rng.h's pcgHash and hashCombine (Jarzynski & Olano 2020), for alpha BLEND's
// stochastic coverage: a number in [0, 1) per fragment and frame from the pixel, the
// frame's jitter (which changes every frame), the eye and the triangle.
uint pcgHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

uint hashCombine(uint seed, uint v) { return pcgHash(v + pcgHash(seed)); }

float coverageNumber(uint instance, uint triangle) {
  uint h = hashCombine(pcgHash(uint(gl_FragCoord.x)), uint(gl_FragCoord.y));
  h = hashCombine(h, floatBitsToUint(frame.jitter[vEye].x));
  h = hashCombine(h, floatBitsToUint(frame.jitter[vEye].y));
  h = hashCombine(hashCombine(hashCombine(h, vEye), instance), triangle);
  return float(h >> 8u) * (1.0 / 16777216.0);
}

vec2 motionVector() {
  vec2 current = vClip.xy / vClip.w;
  vec2 previous = vPreviousClip.xy / vPreviousClip.w;
  return (previous - current) * 0.5 * frame.viewport.xy;
}

void main() {
  GpuMaterial mat = material;
  GpuInstance inst = instances[vInstance];
  bool front = gl_FrontFacing != (inst.info.y != 0u);
  if (!front && mat.flags.y == 0u) discard;  // single-sided: cull back faces
  vec4 base = mat.baseColorFactor * SAMPLE_SLOT(mat, SLOT_BASE_COLOR, uBaseColor, vec4(1.0));
  if (mat.flags.x == ALPHA_MASK && base.a < mat.emissive.w) discard;
  // BLEND: the surface covers the pixel with probability alpha, as the tracer's rays meet
  // it (trace/embree_scene.cpp); averaged over frames, alpha-weighted as blending is.
  if (mat.flags.x == ALPHA_BLEND && coverageNumber(inst.info.x, uint(gl_PrimitiveID)) >= base.a)
    discard;
  vec4 mr = SAMPLE_SLOT(mat, SLOT_METALLIC_ROUGHNESS, uMetallicRoughness, vec4(1.0));
  float occlusion = SAMPLE_SLOT(mat, SLOT_OCCLUSION, uOcclusion, vec4(1.0)).r;
  uint triangle = uint(gl_PrimitiveID);
  vec2 b = rayBarycentrics(inst, triangle);
  outVisibility = uvec4(inst.info.x, triangle, floatBitsToUint(b.x), floatBitsToUint(b.y));
  outNormal = vec4(shadingNormal(mat, front), 1.0);
  outBaseColor = vec4(base.rgb, 1.0 + mat.params.w * (occlusion - 1.0));
  outMaterial = vec4(mat.params.x * mr.b, mat.params.y * mr.g, 0.0, 0.0);
  outEmission = vec4(mat.emissive.rgb * SAMPLE_SLOT(mat, SLOT_EMISSIVE, uEmissive, vec4(1.0)).rgb, 1.0);
  outMotion = motionVector();
}
