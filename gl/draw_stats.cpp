#include "gl/draw_stats.h"

#include "gl/gl_api.h"

namespace photovr::gl {

DrawStats& drawStats() {
  static DrawStats stats;
  return stats;
}

void resetDrawStats() {
  drawStats() = DrawStats{};
}

void drawIndexedTrianglesInstanced(uint32_t indexCount, uint32_t instanceCount) {
  DrawStats& s = drawStats();
  ++s.drawCalls;
  s.instances += instanceCount;
  s.triangles += uint64_t(indexCount / 3) * instanceCount;
  api::DrawElementsInstanced(GL_TRIANGLES, GLsizei(indexCount), GL_UNSIGNED_INT, nullptr,
                             GLsizei(instanceCount));
}

void drawFullscreenTriangle() {
  DrawStats& s = drawStats();
  ++s.drawCalls;
  ++s.instances;
  ++s.triangles;
  api::DrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace photovr::gl
