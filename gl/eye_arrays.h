// Both eyes of a frame as the GL passes take them: 2-layer arrays (layer = eye) of linear
// colour (RGBA32F) and reversed-Z depth (R32F), filled from CPU images. What a frame that
// did not go through the denoiser is uploaded into before the headset compositor.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace photovr::gl {

// Both eyes' linear colour (float RGB(A)) and reversed-Z depth as 2-layer arrays (layer =
// eye), by GL name: what the compositor re-projects (an EyeArrays upload, or the denoiser's
// output).
struct EyeTextures {
  unsigned color = 0, depth = 0;
};

class EyeArrays {
 public:
  EyeArrays(int width, int height);  // cleared to 0
  ~EyeArrays();
  EyeArrays(const EyeArrays&) = delete;
  EyeArrays& operator=(const EyeArrays&) = delete;

  // One eye's colour and depth, rows bottom-up, width x height each; UsageError otherwise.
  void upload(int eye, const std::vector<glm::vec4>& color, const std::vector<float>& depth);

  unsigned color() const { return color_; }
  unsigned depth() const { return depth_; }

 private:
  int width_, height_;
  unsigned color_ = 0, depth_ = 0;
};

}  // namespace photovr::gl
