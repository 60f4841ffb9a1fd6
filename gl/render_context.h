// The GL context a rendering command runs on: --backend, else EGL with OSMesa as fallback.
#pragma once

#include <memory>
#include <string>

#include "gl/context.h"

namespace photovr::gl {

std::unique_ptr<Context> createRenderContext(const std::string& backend);

}  // namespace photovr::gl
