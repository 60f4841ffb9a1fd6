#include "core/heatmap.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <array>
#include <map>

namespace photovr {
namespace {

// 3x5 glyphs, rows top to bottom, 3 bits each (4 = left column).
const std::map<char, std::array<uint8_t, 5>>& font() {
  static const std::map<char, std::array<uint8_t, 5>> glyphs = {
      {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}}, {'2', {7, 1, 7, 4, 7}},
      {'3', {7, 1, 7, 1, 7}}, {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}},
      {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 1, 1}}, {'8', {7, 5, 7, 5, 7}},
      {'9', {7, 5, 7, 1, 7}}, {'-', {0, 0, 7, 0, 0}}, {'+', {0, 2, 7, 2, 0}},
      {'.', {0, 0, 0, 0, 2}}, {'e', {0, 7, 7, 4, 7}}, {' ', {0, 0, 0, 0, 0}},
      {'A', {2, 5, 7, 5, 5}}, {'B', {6, 5, 6, 5, 6}}, {'D', {6, 5, 5, 5, 6}},
      {'E', {7, 4, 6, 4, 7}}, {'H', {5, 5, 7, 5, 5}}, {'I', {7, 2, 2, 2, 7}},
      {'L', {4, 4, 4, 4, 7}}, {'M', {5, 7, 7, 5, 5}}, {'N', {5, 7, 7, 7, 5}},
      {'O', {7, 5, 5, 5, 7}}, {'P', {7, 5, 7, 4, 4}}, {'R', {6, 5, 6, 5, 5}},
      {'S', {7, 4, 7, 1, 7}}, {'T', {7, 2, 2, 2, 2}}, {'V', {5, 5, 5, 5, 2}},
      {'Y', {5, 5, 2, 2, 2}}, {'F', {7, 4, 6, 4, 4}}, {'C', {7, 4, 4, 4, 7}},
      {'G', {7, 4, 5, 5, 7}}, {'U', {5, 5, 5, 5, 7}}, {'W', {5, 5, 7, 7, 5}},
      {'K', {5, 5, 6, 5, 5}}, {'X', {5, 5, 2, 5, 5}}, {'Z', {7, 1, 2, 4, 7}}};
  return glyphs;
}

void setPixel(Image8& img, int x, int y, glm::u8vec3 c) {
  if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
  uint8_t* p = img.at(x, y);
  p[0] = c.r, p[1] = c.g, p[2] = c.b;
}

}  // namespace

glm::u8vec3 heatColor(float t) {
  static const glm::vec3 stops[] = {
      {0, 0, 0}, {0.35f, 0.05f, 0.55f}, {0.85f, 0.15f, 0.2f}, {1.0f, 0.8f, 0.1f}, {1, 1, 1}};
  t = std::clamp(std::isfinite(t) ? t : 1.0f, 0.0f, 1.0f) * 4.0f;
  const int i = std::min(int(t), 3);
  const glm::vec3 c = glm::mix(stops[i], stops[i + 1], t - float(i));
  return glm::u8vec3(glm::round(c * 255.0f));
}

void drawText(Image8& img, int x, int y, const std::string& text, int scale, glm::u8vec3 color) {
  for (char ch : text) {
    const auto it = font().find(ch);
    if (it != font().end())
      for (int row = 0; row < 5; ++row)
        for (int col = 0; col < 3; ++col)
          if (it->second[row] & (4 >> col))
            for (int sy = 0; sy < scale; ++sy)
              for (int sx = 0; sx < scale; ++sx)
                setPixel(img, x + col * scale + sx, y + row * scale + sy, color);
    x += 4 * scale;
  }
}

Image8 heatMapImage(const std::vector<HeatPanel>& panels, float lo, float hi) {
  int width = 0, height = 0;
  for (const HeatPanel& p : panels) width = std::max(width, p.width), height += p.height;
  const int scale = std::max(1, width / 320), barHeight = 14 * scale;
  Image8 img(std::max(width, 1), height + barHeight, 3);
  const float a = std::log10(lo), b = std::log10(hi);
  int y0 = 0;
  for (const HeatPanel& p : panels) {
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x) {
        const float v = p.values[size_t(y) * p.width + x];
        setPixel(img, x, y0 + y, heatColor((std::log10(std::max(v, lo)) - a) / (b - a)));
      }
    drawText(img, 2 * scale, y0 + 2 * scale, p.label, scale, glm::u8vec3(255, 255, 255));
    y0 += p.height;
  }
  for (int x = 0; x < img.width; ++x)
    for (int y = 0; y < 5 * scale; ++y)
      setPixel(img, x, height + y, heatColor(float(x) / img.width));
  for (int d = int(std::ceil(a)); d <= int(std::floor(b)); ++d) {
    const int x = int((float(d) - a) / (b - a) * float(img.width - 1));
    char label[16];
    std::snprintf(label, sizeof label, "1e%+d", d);
    const int textX = std::clamp(x - 8 * scale, 0, img.width - 16 * scale);
    drawText(img, textX, height + 7 * scale, label, scale, glm::u8vec3(255, 255, 255));
  }
  return img;
}

}  // namespace photovr
