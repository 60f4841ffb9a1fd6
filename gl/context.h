// One interface over the three ways photovr gets an OpenGL 4.5 core context (Filament's
// PlatformOSMesa / PlatformEGLHeadless pattern). Nothing above gl/ knows which one runs.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

namespace photovr::gl {

enum class Backend { OSMesa, EGL, GLFW };

Backend parseBackend(const std::string& name);  // "osmesa" | "egl" | "glfw"; else UsageError
std::string backendName(Backend backend);

// A backend that cannot give what photovr needs. The message names the backend, what it
// offered, and what to try instead.
class ContextError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ContextOptions {
  Backend backend = Backend::OSMesa;
  int windowWidth = 1280;  // glfw only
  int windowHeight = 720;  // glfw only
  bool visible = false;    // glfw only
  // glfw only: fullscreen on this monitor (an index into listMonitors(), e.g. the DK2's
  // from pickHeadsetMonitor) at its current mode; -1: a window of the size above.
  int fullscreenMonitor = -1;
  std::string title = "photovr";
};

class Context {
 public:
  virtual ~Context() = default;
  // Creates the context, makes it current, loads the entry points and checks for OpenGL
  // 4.5 core. Throws ContextError.
  static std::unique_ptr<Context> create(const ContextOptions& options);
  // Headless: EGL (a GPU's, or Mesa's llvmpipe), else OSMesa. Why EGL failed goes to
  // 'eglFailure' when OSMesa had to stand in.
  static std::unique_ptr<Context> createHeadless(std::string* eglFailure = nullptr);

  virtual Backend backend() const = 0;
  // Makes this context current and points the entry points at it (contexts of different
  // backends resolve functions differently: OSMesa directly, EGL/GLFW through glvnd).
  void makeCurrent();
  virtual void swapBuffers() {}
  virtual bool shouldClose() const { return false; }
  virtual void* nativeWindow() const { return nullptr; }

  const std::string& version() const { return version_; }
  const std::string& renderer() const { return renderer_; }
  bool hasExtension(const std::string& name) const { return currentContextHasExtension(name); }
  static bool currentContextHasExtension(const std::string& name);

 protected:
  using ProcLoader = void* (*)(const char* name);
  // Loads entry points through 'loader' and verifies the version; called by backends once
  // their context is current.
  void initialize(ProcLoader loader);
  virtual void bindCurrent() = 0;  // the backend's own make-current call
  void releaseEntryPoints();       // destructors: forget the pointers if they were ours

 private:
  std::string version_;
  std::string renderer_;
  ProcLoader loader_ = nullptr;
};

// Backends (each in its own file so their system headers stay apart).
std::unique_ptr<Context> createOSMesaContext(const ContextOptions& options);
std::unique_ptr<Context> createEGLContext(const ContextOptions& options);
std::unique_ptr<Context> createGLFWContext(const ContextOptions& options);

}  // namespace photovr::gl
