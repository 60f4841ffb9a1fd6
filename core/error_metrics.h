// Image error metrics against a reference, on linear RGB images of equal size.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace photovr {

// Relative MSE per pixel, mean over channels of (x - r)^2 / (r^2 + eps): the form used in
// denoising and sampling papers (e.g. Rousselle et al. 2011; Schied et al. 2017), eps = 1e-2
// so that dark pixels do not dominate.
constexpr float kRelMseEpsilon = 1e-2f;
float relMsePixel(const glm::vec3& x, const glm::vec3& reference);
std::vector<float> relMseMap(const std::vector<glm::vec3>& image,
                             const std::vector<glm::vec3>& reference);
double relMse(const std::vector<glm::vec3>& image, const std::vector<glm::vec3>& reference);

// relMSE without the worst 0.1 % of pixels: a path tracer's error is heavy-tailed (one
// caustic sample of 1000x the pixel's value is a firefly that dominates the mean for
// hundreds of samples; in spheres at 120 x 135 one pixel was 65 % of a 32-frame relMSE),
// and a change that lowers the error should show it in the body of the image too, not only
// in where its rare fireflies happen to land.
double trimmedRelMse(const std::vector<glm::vec3>& image, const std::vector<glm::vec3>& reference);

// PSNR in dB of the display images (exposure, Khronos PBR Neutral, sRGB, in [0, 1]): what
// a person compares, and bounded for HDR values.
double psnrDisplay(const std::vector<glm::vec3>& image, const std::vector<glm::vec3>& reference,
                   float exposure = 1.0f);

// Two display images of the headset's panel (8-bit RGBA, equal size) compared where both
// show something: black is what a panel shows outside the lens and where a frame holds
// nothing, so it is left out of the mean and counted apart.
struct PanelDifference {
  double meanLevels = 0.0;  // mean |a - b| in 8-bit levels over the RGB of the shown pixels
  int maxLevels = 0;
  int shown = 0;       // pixels neither image has black
  int blackInOne = 0;  // pixels black in exactly one image
};
PanelDifference panelDifference(const std::vector<glm::u8vec4>& a,
                                const std::vector<glm::u8vec4>& b);

}  // namespace photovr
