#include "gl/eye_arrays.h"

#include <string>

#include "core/error.h"
#include "gl/gl_api.h"
#include "gl/textures.h"

namespace photovr::gl {

EyeArrays::EyeArrays(int width, int height) : width_(width), height_(height) {
  if (width < 1 || height < 1) throw UsageError("eye arrays: empty image");
  color_ = makeArrayTexture(GL_RGBA32F, width, height, 2);
  depth_ = makeArrayTexture(GL_R32F, width, height, 2);
  api::ClearTexImage(color_, 0, GL_RGBA, GL_FLOAT, nullptr);
  api::ClearTexImage(depth_, 0, GL_RED, GL_FLOAT, nullptr);
}

EyeArrays::~EyeArrays() {
  const GLuint t[] = {color_, depth_};
  api::DeleteTextures(2, t);
}

void EyeArrays::upload(int eye, const std::vector<glm::vec4>& color,
                       const std::vector<float>& depth) {
  const size_t n = size_t(width_) * height_;
  if (eye < 0 || eye > 1 || color.size() != n || depth.size() != n)
    throw UsageError("eye arrays: eye must be 0 or 1 and images " + std::to_string(width_) + "x" +
                     std::to_string(height_));
  api::PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  api::TextureSubImage3D(color_, 0, 0, 0, eye, width_, height_, 1, GL_RGBA, GL_FLOAT, color.data());
  api::TextureSubImage3D(depth_, 0, 0, 0, eye, width_, height_, 1, GL_RED, GL_FLOAT, depth.data());
}

}  // namespace photovr::gl
