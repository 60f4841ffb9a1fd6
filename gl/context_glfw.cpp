// A window (for the interactive app); needs a display (X11 or Xvfb).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <string>

#include "gl/context.h"

namespace photovr::gl {
namespace {

void* glfwProc(const char* name) {
  return reinterpret_cast<void*>(glfwGetProcAddress(name));
}

std::string glfwErrorText() {
  const char* text = nullptr;
  glfwGetError(&text);
  return text ? text : "unknown error";
}

class GLFWContextImpl final : public Context {
 public:
  explicit GLFWContextImpl(const ContextOptions& o) {
    if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY"))
      throw ContextError(
          "glfw: no display (DISPLAY is not set); run under a desktop or "
          "xvfb-run, or use --backend egl / osmesa for headless rendering");
    if (!glfwInit())
      throw ContextError("glfw: initialisation failed (" + glfwErrorText() +
                         "); try --backend egl");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, o.visible ? GLFW_TRUE : GLFW_FALSE);
    GLFWmonitor* monitor = nullptr;
    int width = o.windowWidth, height = o.windowHeight;
    if (o.fullscreenMonitor >= 0) {
      int count = 0;
      GLFWmonitor** monitors = glfwGetMonitors(&count);
      if (o.fullscreenMonitor >= count) {
        glfwTerminate();
        throw ContextError("glfw: no monitor " + std::to_string(o.fullscreenMonitor));
      }
      monitor = monitors[o.fullscreenMonitor];
      const GLFWvidmode* mode = glfwGetVideoMode(monitor);
      width = mode->width, height = mode->height;
      glfwWindowHint(GLFW_REFRESH_RATE, mode->refreshRate);
    }
    window_ = glfwCreateWindow(width, height, o.title.c_str(), monitor, nullptr);
    if (!window_) {
      const std::string why = glfwErrorText();
      glfwTerminate();
      throw ContextError("glfw: no OpenGL 4.5 core window (" + why + "); try --backend egl");
    }
    bindCurrent();
    initialize(glfwProc);
  }
  ~GLFWContextImpl() override {
    releaseEntryPoints();
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
  Backend backend() const override { return Backend::GLFW; }
  void bindCurrent() override { glfwMakeContextCurrent(window_); }
  void swapBuffers() override {
    glfwSwapBuffers(window_);
    glfwPollEvents();
  }
  bool shouldClose() const override { return glfwWindowShouldClose(window_); }
  void* nativeWindow() const override { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace

std::unique_ptr<Context> createGLFWContext(const ContextOptions& options) {
  return std::make_unique<GLFWContextImpl>(options);
}

}  // namespace photovr::gl
