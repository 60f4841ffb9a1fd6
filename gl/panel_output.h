// The last pass before the headset's panel (issue 6, item 5c): the Distorter's linear panel
// image -> exposure -> Khronos PBR Neutral -> sRGB, rotated to the panel's scan-out
// orientation, into an RGBA8 texture that is read back (headless: an image file) or
// blitted to the default framebuffer (a window, the DK2 or a desktop mirror).
//
// Reads:  the linear panel, any float RGB(A) 2D texture (Distorter::panelTexture: RGBA16F).
// Writes: RGBA8, sRGB-encoded values (not an sRGB format: the encoding is done in the
//         shader, as core/tonemap.cpp displayColor does it), alpha 1.
//
// Rotation: the DK2's panel is a 1080x1920 portrait panel scanned as such; Linux leaves the
// output unrotated, so the landscape image is turned here (dk2.md §5). 90 is the DK2 case:
// native(xp, yp) = (y, W - 1 - x) for landscape texel (x, y) of a W-wide image.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gl/program.h"

namespace photovr::gl {

// 0, 90, 180 or 270; anything else is a UsageError.
int checkPanelRotation(int degrees);

// Output size of a w x h image turned by 'degrees'.
inline glm::ivec2 rotatedSize(int degrees, int w, int h) {
  return degrees == 90 || degrees == 270 ? glm::ivec2(h, w) : glm::ivec2(w, h);
}

// The source texel (landscape, w x h) an output texel (xo, yo) shows. Texel indices as
// stored (the same rule for GL's bottom-up and an image's top-down rows, as long as input
// and output use the same one). Pure: the shader and the tests share this definition.
inline glm::ivec2 panelSourceTexel(int degrees, int w, int h, int xo, int yo) {
  switch (degrees) {
    case 90:
      return {w - 1 - yo, xo};
    case 180:
      return {w - 1 - xo, h - 1 - yo};
    case 270:
      return {yo, h - 1 - xo};
    default:
      return {xo, yo};
  }
}

class PanelOutput {
 public:
  // Input panels are panelWidth x panelHeight (landscape); the output is turned by
  // rotationDegrees.
  PanelOutput(int panelWidth, int panelHeight, int rotationDegrees);
  ~PanelOutput();
  PanelOutput(const PanelOutput&) = delete;
  PanelOutput& operator=(const PanelOutput&) = delete;

  void run(unsigned linearPanel, float exposure);

  unsigned texture() const { return output_; }  // RGBA8
  int width() const { return size_.x; }         // output (rotated) size
  int height() const { return size_.y; }
  int rotation() const { return rotation_; }
  int panelWidth() const { return panelWidth_; }  // input (landscape) size
  int panelHeight() const { return panelHeight_; }
  std::vector<glm::u8vec4> read() const;  // rows bottom-up

  // Scales the output into the window's default framebuffer, aspect kept (black bars).
  void present(int windowWidth, int windowHeight) const;

 private:
  int panelWidth_, panelHeight_, rotation_;
  glm::ivec2 size_;
  Program program_;
  unsigned output_ = 0, fbo_ = 0;
};

// Waits until every GL command issued so far has completed (glFinish): timing passes apart.
void waitForGpu();

// The default framebuffer's colour (back buffer), rows bottom-up: for screenshots of a
// window after everything, overlay included, has been drawn and before the swap.
std::vector<glm::u8vec4> readDefaultFramebuffer(int width, int height);

}  // namespace photovr::gl
