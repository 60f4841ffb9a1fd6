// Bindings shared by the G-buffer stages.
#include "gbuffer_shared.h"

layout(std430, binding = 0) readonly buffer Instances { GpuInstance instances[]; };
layout(std430, binding = 1) readonly buffer Materials { GpuMaterial materials[]; };
layout(std430, binding = 2) readonly buffer MeshPositions { float meshPositions[]; };
layout(std430, binding = 3) readonly buffer MeshIndices { uint meshIndices[]; };
layout(std140, binding = 4) uniform Frame { FrameUniforms frame; };
