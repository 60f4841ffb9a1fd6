// Dear ImGui on the view window (Debian's libimgui 1.86 with its GLFW and OpenGL3 backends
// compiled in). Only the backends' set-up lives here; the panels are drawn by the caller
// with ImGui:: calls between newFrame() and render().
//
// GL loading: ImGui_ImplOpenGL3_Init always runs its bundled gl3w loader (imgl3wInit),
// which dlopens libGL.so.1 and resolves through glXGetProcAddressARB. Right after it we
// re-point that table through GLFW's proc-address function (imgl3wInit2), the same
// function our own entry points were loaded with (gl/context_glfw.cpp), so both tables
// resolve against the one context. libGL is never linked (platform.md).
#pragma once

#include "gl/context.h"

namespace photovr::app {

class ViewOverlay {
 public:
  explicit ViewOverlay(gl::Context& context);  // glfw backend only; throws ContextError
  ~ViewOverlay();
  ViewOverlay(const ViewOverlay&) = delete;
  ViewOverlay& operator=(const ViewOverlay&) = delete;

  void newFrame();
  void render();  // into the current (default) framebuffer
  bool wantsMouse() const;
  bool wantsKeyboard() const;
};

}  // namespace photovr::app
