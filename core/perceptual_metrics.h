// A perceptual image metric for the bench: SSIM (Wang, Bovik, Sheikh, Simoncelli, "Image
// Quality Assessment: From Error Visibility to Structural Similarity", IEEE TIP 13(4), 2004).
//
// Why SSIM and not FLIP (Andersson et al. 2020): both are full-reference and written from
// their papers in a few dozen lines, but SSIM has one closed form with published constants
// (K1, K2, the 11x11 Gaussian window) that tests can check exactly (identical images give
// 1, two constant images give (2ab + C1) / (a^2 + b^2 + C1)), its value is comparable with
// the rendering literature that reports it, and it is cheap (five separable filters). FLIP's pooled
// value depends on an assumed viewing distance and display (pixels per degree), which for a
// headset's lens-distorted eye buffer has no single value. SSIM's blind spot, that it ignores hue,
// matters little for the noise the bench measures, which is mostly luminance noise.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace photovr {

// Wang et al. 2004, sec. III-B/C: K1 = 0.01, K2 = 0.03, dynamic range L = 1 (values in
// [0, 1]), circular-symmetric Gaussian weights, 11 x 11, sigma 1.5, normalised to sum 1.
constexpr double kSsimK1 = 0.01, kSsimK2 = 0.03;
constexpr int kSsimWindow = 11;
constexpr double kSsimSigma = 1.5;

// Mean SSIM (eq. 13, "MSSIM") of two single-channel images of width x height (row-major,
// any row order), values in [0, 1], over every window that lies wholly inside the image (as
// the authors' reference code, filter2(..., 'valid')). Both sides must be at least
// kSsimWindow; throws std::invalid_argument otherwise or when the sizes disagree.
// Symmetric in its arguments; exactly 1 for identical images.
double ssim(const std::vector<float>& x, const std::vector<float>& y, int width, int height);

// Display luminance in [0, 1]: exposure, Khronos PBR Neutral, sRGB 8-bit (as psnrDisplay
// and the written PNGs), then Rec. 709 luma of the encoded values, Y' = 0.2126 R' + 0.7152 G'
// + 0.0722 B' — the grey-level image SSIM was designed and validated on.
std::vector<float> displayLuminance(const std::vector<glm::vec3>& linear, float exposure = 1.0f);

// SSIM of the display luminance of two linear RGB images (one eye each).
double ssimDisplay(const std::vector<glm::vec3>& image, const std::vector<glm::vec3>& reference,
                   int width, int height, float exposure = 1.0f);

}  // namespace photovr
