// Every draw photovr issues goes through these wrappers, which count what was drawn, so
// tests can check e.g. "one draw call per mesh for both eyes".
#pragma once

#include <cstdint>

namespace photovr::gl {

struct DrawStats {
  uint64_t drawCalls = 0;
  uint64_t instances = 0;  // summed instance counts of the draws
  uint64_t triangles = 0;  // summed triangles x instances
};

DrawStats& drawStats();
void resetDrawStats();

void drawIndexedTrianglesInstanced(uint32_t indexCount, uint32_t instanceCount);
void drawFullscreenTriangle();

}  // namespace photovr::gl
