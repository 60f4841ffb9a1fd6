#include "gl/window_input.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace photovr::gl {

WindowInput WindowInputReader::poll() {
  WindowInput in;
  auto* window = static_cast<GLFWwindow*>(context_.nativeWindow());
  if (!window || context_.backend() != Backend::GLFW) return in;
  const auto down = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS; };
  in.forward = down(GLFW_KEY_W), in.back = down(GLFW_KEY_S);
  in.left = down(GLFW_KEY_A), in.right = down(GLFW_KEY_D);
  in.up = down(GLFW_KEY_E), in.down = down(GLFW_KEY_Q);
  in.fast = down(GLFW_KEY_LEFT_SHIFT) || down(GLFW_KEY_RIGHT_SHIFT);
  in.quitPressed = down(GLFW_KEY_ESCAPE);
  const bool save = down(GLFW_KEY_F12);
  in.savePressed = save && !saveWasDown_;
  saveWasDown_ = save;
  glm::dvec2 cursor;
  glfwGetCursorPos(window, &cursor.x, &cursor.y);
  in.dragging = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  if (in.dragging && hadCursor_) in.mouseDelta = glm::vec2(cursor - lastCursor_);
  lastCursor_ = cursor;
  hadCursor_ = true;
  glfwGetFramebufferSize(window, &in.framebufferSize.x, &in.framebufferSize.y);
  return in;
}

}  // namespace photovr::gl
