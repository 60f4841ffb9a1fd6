#include "core/error_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/image_io.h"
#include "core/tonemap.h"

namespace photovr {

float relMsePixel(const glm::vec3& x, const glm::vec3& r) {
  float sum = 0.0f;
  for (int k = 0; k < 3; ++k) {
    const float d = x[k] - r[k];
    sum += d * d / (r[k] * r[k] + kRelMseEpsilon);
  }
  return sum / 3.0f;
}

std::vector<float> relMseMap(const std::vector<glm::vec3>& image,
                             const std::vector<glm::vec3>& reference) {
  std::vector<float> map(image.size());
  for (size_t i = 0; i < image.size(); ++i) map[i] = relMsePixel(image[i], reference[i]);
  return map;
}

double relMse(const std::vector<glm::vec3>& image, const std::vector<glm::vec3>& reference) {
  double sum = 0.0;
  for (size_t i = 0; i < image.size(); ++i) sum += relMsePixel(image[i], reference[i]);
  return image.empty() ? 0.0 : sum / double(image.size());
}

double trimmedRelMse(const std::vector<glm::vec3>& image, const std::vector<glm::vec3>& ref) {
  std::vector<float> m = relMseMap(image, ref);
  const size_t keep = m.size() - m.size() / 1000;
  if (keep == 0) return 0.0;
  std::nth_element(m.begin(), m.begin() + keep, m.end());
  double sum = 0.0;
  for (size_t i = 0; i < keep; ++i) sum += m[i];
  return sum / double(keep);
}

double psnrDisplay(const std::vector<glm::vec3>& image, const std::vector<glm::vec3>& reference,
                   float exposure) {
  double sum = 0.0;
  for (size_t i = 0; i < image.size(); ++i) {
    const glm::vec3 a = glm::vec3(displayColor(image[i], exposure)) / 255.0f;
    const glm::vec3 b = glm::vec3(displayColor(reference[i], exposure)) / 255.0f;
    const glm::vec3 d = a - b;
    sum += glm::dot(d, d) / 3.0;
  }
  const double mse = image.empty() ? 0.0 : sum / double(image.size());
  return mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : 99.0;  // 99 dB stands for identical
}

PanelDifference panelDifference(const std::vector<glm::u8vec4>& a,
                                const std::vector<glm::u8vec4>& b) {
  PanelDifference d;
  double sum = 0.0;
  const auto isBlack = [](const glm::u8vec4& p) { return p.r == 0 && p.g == 0 && p.b == 0; };
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    d.blackInOne += isBlack(a[i]) != isBlack(b[i]);
    if (isBlack(a[i]) || isBlack(b[i])) continue;
    ++d.shown;
    for (int c = 0; c < 3; ++c) {
      const int diff = std::abs(int(a[i][c]) - int(b[i][c]));
      sum += diff;
      d.maxLevels = std::max(d.maxLevels, diff);
    }
  }
  d.meanLevels = d.shown > 0 ? sum / (3.0 * d.shown) : 0.0;
  return d;
}

}  // namespace photovr
