#include "gl/gl_api.h"

#include <string>

namespace photovr::gl::api {

#define PHOTOVR_GL_DEFINE(type, name) type name = nullptr;
PHOTOVR_GL_FUNCTIONS(PHOTOVR_GL_DEFINE)
#undef PHOTOVR_GL_DEFINE

const char* load(ProcLoader loader) {
#define PHOTOVR_GL_LOAD(type, name)                  \
  name = reinterpret_cast<type>(loader("gl" #name)); \
  if (!name) return "gl" #name;
  PHOTOVR_GL_FUNCTIONS(PHOTOVR_GL_LOAD)
#undef PHOTOVR_GL_LOAD
  return "";
}

}  // namespace photovr::gl::api
