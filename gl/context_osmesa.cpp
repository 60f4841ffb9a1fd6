// Software, headless: Mesa's llvmpipe through OSMesa, the default for tests.
#include <GL/glcorearb.h>  // before osmesa.h, which includes GL/gl.h (platform.md)
#include <GL/osmesa.h>

#include <vector>

#include "gl/context.h"

namespace photovr::gl {
namespace {

void* osmesaProc(const char* name) {
  return reinterpret_cast<void*>(OSMesaGetProcAddress(name));
}

class OSMesaContextImpl final : public Context {
 public:
  OSMesaContextImpl() {
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           0,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           4,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           5,
                           0};
    ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!ctx_)
      throw ContextError(
          "osmesa: could not create an OpenGL 4.5 core context (is libosmesa6 >= 20 "
          "installed?); try --backend egl");
    bindCurrent();
    initialize(osmesaProc);
  }
  ~OSMesaContextImpl() override {
    releaseEntryPoints();
    if (OSMesaGetCurrentContext() == ctx_) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    OSMesaDestroyContext(ctx_);
  }
  Backend backend() const override { return Backend::OSMesa; }
  void bindCurrent() override {
    // photovr renders into its own framebuffer objects; the default buffer is a token.
    if (!OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, kSide, kSide))
      throw ContextError("osmesa: OSMesaMakeCurrent failed");
  }

 private:
  static constexpr int kSide = 8;
  OSMesaContext ctx_ = nullptr;
  std::vector<unsigned char> buffer_ = std::vector<unsigned char>(kSide * kSide * 4);
};

}  // namespace

std::unique_ptr<Context> createOSMesaContext(const ContextOptions&) {
  return std::make_unique<OSMesaContextImpl>();
}

}  // namespace photovr::gl
