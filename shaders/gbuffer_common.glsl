// Bindings shared by the G-buffer stages.
#include "gbuffer_shared.h"

layout(std430, binding = 0) readonly buffer Instances { GpuInstance instances[]; };
layout(std430, binding = 2) readonly buffer MeshPositions { float meshPositions[]; };
layout(std430, binding = 3) readonly buffer MeshIndices { uint meshIndices[]; };
layout(std140, binding = 4) uniform Frame { FrameUniforms frame; };
// The draw's material, bound as a uniform range of the material array. A uniform block,
// not a storage buffer: llvmpipe masks storage loads in helper invocations, which then
// see zeros, corrupting the texture-coordinate derivatives along triangle edges.
layout(std140, binding = 5) uniform MaterialBlock { GpuMaterial material; };
