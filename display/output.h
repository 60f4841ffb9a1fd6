// Where the compositor's panel image goes: one interface, three outputs. The headset's own
// panel and a desktop mirror are both a window (the DK2 is a monitor: the window goes
// fullscreen on it, gl/headset_monitor.h); headless runs write image files.
#pragma once

#include <functional>
#include <string>

#include <glm/glm.hpp>

#include "gl/panel_output.h"

namespace photovr::display {

class DisplayOutput {
 public:
  virtual ~DisplayOutput() = default;
  // Frame 'frame's panel image, as the panel output holds it (rotated to the scan-out).
  virtual void show(const gl::PanelOutput& panel, int frame) = 0;
};

// The current context's window: the panel scaled into its framebuffer, aspect kept. The
// caller swaps buffers (after drawing an overlay, if any).
class WindowOutput final : public DisplayOutput {
 public:
  explicit WindowOutput(std::function<glm::ivec2()> framebufferSize)
      : framebufferSize_(std::move(framebufferSize)) {}
  void show(const gl::PanelOutput& panel, int frame) override;

 private:
  std::function<glm::ivec2()> framebufferSize_;
};

// DIR/NNNN_panel.png per frame (written whole, core/files.h).
class ImageFileOutput final : public DisplayOutput {
 public:
  explicit ImageFileOutput(std::string dir) : dir_(std::move(dir)) {}
  void show(const gl::PanelOutput& panel, int frame) override;
  std::string pathOf(int frame) const;

 private:
  std::string dir_;
};

}  // namespace photovr::display
