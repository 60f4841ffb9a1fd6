#include "app/view_overlay.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

// The bundled gl3w loader's re-initialisation entry point (imgui_impl_opengl3_loader.h,
// compiled into libimgui.a); declared here because that header also defines GL macros.
extern "C" int imgl3wInit2(GLFWglproc (*proc)(const char* name));

namespace photovr::app {

ViewOverlay::ViewOverlay(gl::Context& context) {
  auto* window = static_cast<GLFWwindow*>(context.nativeWindow());
  if (!window || context.backend() != gl::Backend::GLFW)
    throw gl::ContextError("view: the overlay needs a window (glfw backend)");
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
  ImGui::StyleColorsDark();
  if (!ImGui_ImplGlfw_InitForOpenGL(window, true) || !ImGui_ImplOpenGL3_Init("#version 450 core") ||
      imgl3wInit2(glfwGetProcAddress) != 0) {
    ImGui::DestroyContext();
    throw gl::ContextError(
        "view: Dear ImGui could not load OpenGL (its loader needs libGL.so.1, from libgl1)");
  }
}

ViewOverlay::~ViewOverlay() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void ViewOverlay::newFrame() {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void ViewOverlay::render() {
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

bool ViewOverlay::wantsMouse() const {
  return ImGui::GetIO().WantCaptureMouse;
}

bool ViewOverlay::wantsKeyboard() const {
  return ImGui::GetIO().WantCaptureKeyboard;
}

}  // namespace photovr::app
