#include "display/output.h"

#include <cstdio>

#include "core/image_io.h"

namespace photovr::display {

void WindowOutput::show(const gl::PanelOutput& panel, int) {
  const glm::ivec2 size = framebufferSize_();
  panel.present(size.x, size.y);
}

std::string ImageFileOutput::pathOf(int frame) const {
  char name[32];
  std::snprintf(name, sizeof name, "/%04d_panel.png", frame);
  return dir_ + name;
}

void ImageFileOutput::show(const gl::PanelOutput& panel, int frame) {
  writeImage(pathOf(frame), flipToImage(panel.read(), panel.width(), panel.height()));
}

}  // namespace photovr::display
