// Headless EGL: Mesa's surfaceless platform, else the device platform (the path NVIDIA's
// driver offers on a machine without a display). No window surface is ever created.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <string>
#include <vector>

#include "gl/context.h"

namespace photovr::gl {
namespace {

void* eglProc(const char* name) {
  return reinterpret_cast<void*>(eglGetProcAddress(name));
}

std::string eglErrorText() {
  char buf[16];
  snprintf(buf, sizeof buf, "0x%04X", unsigned(eglGetError()));
  return buf;
}

bool hasToken(const char* list, const std::string& token) {
  if (!list) return false;
  const std::string s = std::string(" ") + list + " ";
  return s.find(" " + token + " ") != std::string::npos;
}

// Surfaceless first (Mesa), then the first EGL device (NVIDIA and Mesa's software device).
EGLDisplay openHeadlessDisplay(std::string& platform) {
  const char* clientExts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglProc("eglGetPlatformDisplayEXT"));
  if (!getPlatformDisplay) return EGL_NO_DISPLAY;
  if (hasToken(clientExts, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) {
      platform = "surfaceless";
      return d;
    }
  }
  auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglProc("eglQueryDevicesEXT"));
  if (!queryDevices || !hasToken(clientExts, "EGL_EXT_platform_device")) return EGL_NO_DISPLAY;
  EGLDeviceEXT devices[16];
  EGLint count = 0;
  if (!queryDevices(16, devices, &count)) return EGL_NO_DISPLAY;
  for (EGLint i = 0; i < count; ++i) {
    EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
    if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) {
      platform = "device " + std::to_string(i);
      return d;
    }
  }
  return EGL_NO_DISPLAY;
}

class EGLContextImpl final : public Context {
 public:
  EGLContextImpl() {
    std::string platform;
    display_ = openHeadlessDisplay(platform);
    if (display_ == EGL_NO_DISPLAY)
      throw ContextError(
          "egl: no headless EGL display (neither surfaceless nor device "
          "platform initialised, error " +
          eglErrorText() + "); try --backend osmesa");
    if (!eglBindAPI(EGL_OPENGL_API))
      throw ContextError("egl: the " + platform +
                         " display offers no desktop OpenGL; try "
                         "--backend osmesa");
    const EGLint ctxAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                 4,
                                 EGL_CONTEXT_MINOR_VERSION,
                                 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                 EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                 EGL_NONE};
    context_ = eglCreateContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, ctxAttribs);
    if (context_ == EGL_NO_CONTEXT)
      throw ContextError("egl: the " + platform +
                         " display refused an OpenGL 4.5 core context "
                         "(error " +
                         eglErrorText() + "); try --backend osmesa");
    bindCurrent();
    initialize(eglProc);
  }
  ~EGLContextImpl() override {
    releaseEntryPoints();
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
  Backend backend() const override { return Backend::EGL; }
  void bindCurrent() override {
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      throw ContextError("egl: eglMakeCurrent without a surface failed (error " + eglErrorText() +
                         "); try --backend osmesa");
  }

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<Context> createEGLContext(const ContextOptions&) {
  return std::make_unique<EGLContextImpl>();
}

}  // namespace photovr::gl
