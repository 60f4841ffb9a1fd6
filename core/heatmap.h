// False-colour error images with a labelled logarithmic scale bar, for people.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/image_io.h"

namespace photovr {

// Black -> purple -> red -> yellow -> white, monotonic in luminance (so it survives
// grey-scale printing), t in [0, 1].
glm::u8vec3 heatColor(float t);

struct HeatPanel {
  std::string label;  // drawn in the panel's corner (A-Z, 0-9, space, - + . e)
  int width = 0, height = 0;
  std::vector<float> values;  // top-down rows
};

// Panels stacked vertically, values mapped log10 from [lo, hi], with a scale bar below.
Image8 heatMapImage(const std::vector<HeatPanel>& panels, float lo, float hi);

// Draws text with a 3x5 pixel font scaled by 'scale' at (x, y) (top-left).
void drawText(Image8& image, int x, int y, const std::string& text, int scale,
              glm::u8vec3 color = glm::u8vec3(255));

}  // namespace photovr
