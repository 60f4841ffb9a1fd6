#include "gl/context.h"

#include "core/error.h"
#include "gl/gl_api.h"

namespace photovr::gl {

Backend parseBackend(const std::string& name) {
  if (name == "osmesa") return Backend::OSMesa;
  if (name == "egl") return Backend::EGL;
  if (name == "glfw") return Backend::GLFW;
  throw UsageError("--backend: unknown backend '" + name + "' (expected osmesa, egl or glfw)");
}

std::string backendName(Backend backend) {
  switch (backend) {
    case Backend::OSMesa:
      return "osmesa";
    case Backend::EGL:
      return "egl";
    case Backend::GLFW:
      return "glfw";
  }
  return "?";
}

std::unique_ptr<Context> Context::createHeadless(std::string* eglFailure) {
  try {
    return create({Backend::EGL});
  } catch (const ContextError& e) {
    if (eglFailure) *eglFailure = e.what();
    return create({Backend::OSMesa});
  }
}

std::unique_ptr<Context> Context::create(const ContextOptions& options) {
  switch (options.backend) {
    case Backend::OSMesa:
      return createOSMesaContext(options);
    case Backend::EGL:
      return createEGLContext(options);
    case Backend::GLFW:
      return createGLFWContext(options);
  }
  throw ContextError("unknown backend");
}

static std::string otherBackends(Backend b) {
  return b == Backend::OSMesa ? "--backend egl" : "--backend osmesa (software, always headless)";
}

namespace {
const Context* entryPointsOwner = nullptr;  // whose loader filled gl::api last
}

void Context::makeCurrent() {
  bindCurrent();
  if (entryPointsOwner != this && loader_) {
    api::load(loader_);
    entryPointsOwner = this;
  }
}

void Context::releaseEntryPoints() {
  if (entryPointsOwner == this) entryPointsOwner = nullptr;
}

void Context::initialize(ProcLoader loader) {
  loader_ = loader;
  entryPointsOwner = this;
  const std::string name = backendName(backend());
  auto getString = reinterpret_cast<PFNGLGETSTRINGPROC>(loader("glGetString"));
  const char* v = getString ? reinterpret_cast<const char*>(getString(GL_VERSION)) : nullptr;
  version_ = v ? v : "(none)";
  const std::string missing = api::load(loader);
  GLint major = 0, minor = 0;
  if (missing.empty()) {
    api::GetIntegerv(GL_MAJOR_VERSION, &major);
    api::GetIntegerv(GL_MINOR_VERSION, &minor);
    renderer_ = reinterpret_cast<const char*>(api::GetString(GL_RENDERER));
  }
  if (!missing.empty() || major * 10 + minor < 45)
    throw ContextError(name + ": photovr needs OpenGL 4.5 core, the backend offered '" + version_ +
                       "'" + (missing.empty() ? "" : " without " + missing) + "; try " +
                       otherBackends(backend()));
}

bool Context::currentContextHasExtension(const std::string& ext) {
  GLint n = 0;
  api::GetIntegerv(GL_NUM_EXTENSIONS, &n);
  for (GLint i = 0; i < n; ++i)
    if (ext == reinterpret_cast<const char*>(api::GetStringi(GL_EXTENSIONS, GLuint(i))))
      return true;
  return false;
}

}  // namespace photovr::gl
