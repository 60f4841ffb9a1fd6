// Keyboard and mouse of a window context (the glfw backend), as plain state for the app:
// nothing above gl/ sees the windowing library. Other backends have no window and report
// nothing pressed.
#pragma once

#include <glm/glm.hpp>

#include "gl/context.h"

namespace photovr::gl {

struct WindowInput {
  glm::vec2 mouseDelta{0.0f};  // pixels since the last poll, +y down; only while dragging
  bool dragging = false;       // right mouse button held (mouse-look)
  bool forward = false, back = false, left = false, right = false;  // W S A D
  bool up = false, down = false, fast = false;                      // E Q Shift
  bool savePressed = false;  // F12 went down since the last poll
  bool quitPressed = false;  // Escape
  glm::ivec2 framebufferSize{0};
};

class WindowInputReader {
 public:
  explicit WindowInputReader(Context& context) : context_(context) {}
  // Reads the current state; events are pumped by Context::swapBuffers.
  WindowInput poll();

 private:
  Context& context_;
  glm::dvec2 lastCursor_{0.0};
  bool hadCursor_ = false, saveWasDown_ = false;
};

}  // namespace photovr::gl
