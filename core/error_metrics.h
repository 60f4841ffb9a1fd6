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

// PSNR in dB of the display images (exposure, Khronos PBR Neutral, sRGB, in [0, 1]): what
// a person compares, and bounded for HDR values.
double psnrDisplay(const std::vector<glm::vec3>& image, const std::vector<glm::vec3>& reference,
                   float exposure = 1.0f);

}  // namespace photovr
