#include "gl/render_context.h"

#include <iostream>

#include "core/huge_pages.h"

namespace photovr::gl {

std::unique_ptr<Context> createRenderContext(const std::string& backend) {
  std::unique_ptr<gl::Context> ctx;
  if (!backend.empty()) {
    ctx = gl::Context::create({gl::parseBackend(backend)});
  } else {
    std::string eglFailure;
    ctx = gl::Context::createHeadless(&eglFailure);
    if (!eglFailure.empty()) std::cerr << "photovr: " << eglFailure << "; using osmesa\n";
  }
  std::cerr << "photovr: " << gl::backendName(ctx->backend()) << ", OpenGL " << ctx->version()
            << ", " << ctx->renderer() << (mallocUsesHugePages() ? "; malloc on huge pages" : "")
            << "\n";
  return ctx;
}

}  // namespace photovr::gl
