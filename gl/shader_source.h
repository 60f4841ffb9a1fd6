// One loader for shader sources: embedded in the binary, or read from the directory named
// by PHOTOVR_SHADER_DIR when it is set (edit-and-rerun during development).
// #include "name" lines are expanded recursively, each file at most once.
#pragma once

#include <string>

namespace photovr::gl {

std::string shaderSource(const std::string& name);

}  // namespace photovr::gl
