#include "app/gl_context.h"

#include <iostream>

#include "core/huge_pages.h"

namespace photovr::app {

std::unique_ptr<gl::Context> createRenderContext(const std::string& backend) {
  std::unique_ptr<gl::Context> ctx;
  if (!backend.empty()) {
    ctx = gl::Context::create({gl::parseBackend(backend)});
  } else {
    try {
      ctx = gl::Context::create({gl::Backend::EGL});
    } catch (const gl::ContextError& e) {
      std::cerr << "photovr: " << e.what() << "; using osmesa\n";
      ctx = gl::Context::create({gl::Backend::OSMesa});
    }
  }
  std::cerr << "photovr: " << gl::backendName(ctx->backend()) << ", OpenGL " << ctx->version()
            << ", " << ctx->renderer() << (mallocUsesHugePages() ? "; malloc on huge pages" : "")
            << "\n";
  return ctx;
}

}  // namespace photovr::app
