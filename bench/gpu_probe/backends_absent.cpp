// The GPU probe's build has the EGL backend only (bench/gpu_probe/CMakeLists.txt).
#include "gl/context.h"

namespace photovr::gl {

std::unique_ptr<Context> createOSMesaContext(const ContextOptions&) {
  throw ContextError("osmesa: not in the GPU probe's build (EGL only)");
}

std::unique_ptr<Context> createGLFWContext(const ContextOptions&) {
  throw ContextError("glfw: not in the GPU probe's build (EGL only)");
}

}  // namespace photovr::gl
