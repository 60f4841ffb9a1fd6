// Stereo-instanced G-buffer, vertex stage: instance i of a draw is eye (i & 1) of scene
// instance firstInstance + (i >> 1), so ONE draw call covers every instance of a mesh in
// both eyes. The eye is routed to its layer with gl_Layer (ARB_shader_viewport_layer_array)
// or, without it, to its half of a side-by-side target, clipped by gl_ClipDistance.
#include "gbuffer_common.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inTangent;
layout(location = 3) in vec2 inUv0;
layout(location = 4) in vec2 inUv1;
layout(location = 5) in vec3 inPreviousPosition;  // a skinned mesh's last pose; else inPosition

uniform uint uFirstInstance;

out vec3 vNormal;
out vec4 vTangent;
out vec2 vUv0;
out vec2 vUv1;
out vec4 vClip;          // unjittered, this frame
out vec4 vPreviousClip;  // unjittered, last frame
flat out uint vEye;
flat out uint vInstance;

#ifndef PHOTOVR_LAYERED
out float gl_ClipDistance[2];
#endif

void main() {
  uint eye = uint(gl_InstanceID) & 1u;
  uint instance = uFirstInstance + (uint(gl_InstanceID) >> 1);
  GpuInstance inst = instances[instance];
  vec4 world = inst.model * vec4(inPosition, 1.0);
  vec4 clip = frame.viewProjection[eye] * world;
  mat3 normalModel = mat3(inst.normalModel);
  vNormal = normalModel * inNormal;
  vTangent = vec4(mat3(inst.model) * inTangent.xyz, inTangent.w);
  vUv0 = inUv0;
  vUv1 = inUv1;
  vClip = frame.viewProjectionUnjittered[eye] * world;
  vPreviousClip =
      frame.previousViewProjection[eye] * inst.previousModel * vec4(inPreviousPosition, 1.0);
  vEye = eye;
  vInstance = instance;
#ifdef PHOTOVR_LAYERED
  gl_Layer = int(eye);
  gl_Position = clip;
#else
  // Keep -w <= x <= w of the eye's own frustum, then squeeze it into its half.
  gl_ClipDistance[0] = clip.w + clip.x;
  gl_ClipDistance[1] = clip.w - clip.x;
  gl_Position = vec4(0.5 * clip.x + (eye == 0u ? -0.5 : 0.5) * clip.w, clip.yzw);
#endif
}
