#include "hmd/lens_maps.h"

#include <algorithm>
#include <cmath>

namespace photovr::hmd {
namespace {

constexpr Channel kChannels[3] = {Channel::Red, Channel::Green, Channel::Blue};

bool anyChannelSeen(const LensModel& m, const EyeBufferSpec& s, const glm::dvec2& tan) {
  return std::any_of(std::begin(kChannels), std::end(kChannels),
                     [&](Channel c) { return lensSees(m, s.eye, tanToScreen(m, s.eye, tan, c)); });
}

// Max filter over a (2r+1)^2 window: visible pixels grow by r.
std::vector<uint8_t> dilate(const std::vector<uint8_t>& visible, int w, int h, int r) {
  std::vector<uint8_t> rows(visible.size(), 0), out(visible.size(), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int dx = std::max(0, x - r); dx <= std::min(w - 1, x + r); ++dx)
        rows[y * w + x] |= visible[y * w + dx];
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int dy = std::max(0, y - r); dy <= std::min(h - 1, y + r); ++dy)
        out[y * w + x] |= rows[dy * w + x];
  return out;
}

glm::dvec2 pixelCentreTan(const EyeBufferSpec& s, int x, int y) {
  return eyeBufferToTan(s.fov, s.width, s.height, glm::dvec2(x + 0.5, y + 0.5));
}

// Display pixels per tan-angle area at a screen point: |det| of d(screen px)/d(tan).
double displayPixelsPerTanArea(const LensModel& m, Eye eye, const glm::dvec2& screen) {
  const double h = 1e-5;  // NDC; the map is smooth, central differences err ~h^2
  const glm::dvec2 dx = (screenToTan(m, eye, screen + glm::dvec2(h, 0)) -
                         screenToTan(m, eye, screen - glm::dvec2(h, 0))) /
                        (2 * h);
  const glm::dvec2 dy = (screenToTan(m, eye, screen + glm::dvec2(0, h)) -
                         screenToTan(m, eye, screen - glm::dvec2(0, h))) /
                        (2 * h);
  const double tanPerNdcArea = std::abs(dx.x * dy.y - dx.y * dy.x);
  const double pixelsPerNdcArea = 0.25 * m.panel.eyeWidth() * m.panel.eyeHeight();
  return pixelsPerNdcArea / tanPerNdcArea;
}

}  // namespace

std::vector<uint8_t> hiddenAreaMask(const LensModel& m, const EyeBufferSpec& s, int r) {
  std::vector<uint8_t> visible(size_t(s.width) * s.height);
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x)
      visible[size_t(y) * s.width + x] = anyChannelSeen(m, s, pixelCentreTan(s, x, y));
  if (r > 0) visible = dilate(visible, s.width, s.height, r);
  for (uint8_t& v : visible) v = !v;
  return visible;
}

std::vector<uint8_t> distortionFootprint(const LensModel& m, const EyeBufferSpec& s) {
  std::vector<uint8_t> read(size_t(s.width) * s.height, 0);
  const int dw = m.panel.eyeWidth(), dh = m.panel.eyeHeight();
  auto mark = [&](int x, int y) {
    if (x >= 0 && y >= 0 && x < s.width && y < s.height) read[size_t(y) * s.width + x] = 1;
  };
  for (int py = 0; py < dh; ++py)
    for (int px = 0; px < dw; ++px) {
      const glm::dvec2 screen((px + 0.5) * 2.0 / dw - 1.0, (py + 0.5) * 2.0 / dh - 1.0);
      if (!lensSees(m, s.eye, screen)) continue;
      for (Channel c : kChannels) {
        // Bilinear taps: the texels whose centres surround the sample point.
        const glm::dvec2 p =
            tanToEyeBuffer(s.fov, s.width, s.height, screenToTan(m, s.eye, screen, c)) - 0.5;
        const int x0 = int(std::floor(p.x)), y0 = int(std::floor(p.y));
        mark(x0, y0), mark(x0 + 1, y0), mark(x0, y0 + 1), mark(x0 + 1, y0 + 1);
      }
    }
  return read;
}

std::vector<float> lensDensity(const LensModel& m, const EyeBufferSpec& s) {
  const std::vector<uint8_t> hidden = hiddenAreaMask(m, s);
  // Eye-buffer pixels per tan-angle area: constant over the buffer.
  const double bufferPixelsPerTanArea =
      s.width * s.height / (double(s.fov.left + s.fov.right) * (s.fov.up + s.fov.down));
  std::vector<float> density(hidden.size(), 0.0f);
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const size_t i = size_t(y) * s.width + x;
      if (hidden[i]) continue;
      const glm::dvec2 screen = tanToScreen(m, s.eye, pixelCentreTan(s, x, y));
      density[i] = float(displayPixelsPerTanArea(m, s.eye, screen) / bufferPixelsPerTanArea);
    }
  return density;
}

std::vector<uint16_t> lensMatchedSpp(const LensModel& m, const EyeBufferSpec& s, int maxSpp) {
  const std::vector<float> density = lensDensity(m, s);
  const float top = *std::max_element(density.begin(), density.end());
  std::vector<uint16_t> spp(density.size(), 0);
  if (top <= 0.0f) return spp;
  for (size_t i = 0; i < density.size(); ++i)
    if (density[i] > 0.0f)
      spp[i] = uint16_t(std::clamp(int(std::ceil(maxSpp * density[i] / top - 1e-6)), 1, maxSpp));
  return spp;
}

std::vector<uint16_t> thesisZoneSpp(int width, int height, int maxSpp) {
  std::vector<uint16_t> spp(size_t(width) * height);
  const double m = 0.4 * width, extra = maxSpp - 1;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double d = std::hypot(x + 0.5 - 0.5 * width, y + 0.5 - 0.5 * height);
      const double nd = d / (0.5 * width);
      double v = 1.0 + std::ceil(0.125 * (1.0 - nd) * extra);
      if (d <= m) v += std::ceil((1.0 - (d / m) * (d / m)) * extra);
      spp[size_t(y) * width + x] = uint16_t(std::clamp(int(v), 1, maxSpp));
    }
  return spp;
}

}  // namespace photovr::hmd
