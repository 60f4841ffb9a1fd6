#include "hmd/lens_maps.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace photovr::hmd {
namespace {

constexpr Channel kChannels[3] = {Channel::Red, Channel::Green, Channel::Blue};

bool anyChannelSeen(const LensModel& m, const EyeBufferSpec& s, const glm::dvec2& tan) {
  return std::any_of(std::begin(kChannels), std::end(kChannels),
                     [&](Channel c) { return lensSees(m, s.eye, tanToScreen(m, s.eye, tan, c)); });
}

// Max filter along one axis over a (2r+1) window, as a running count of visible pixels:
// O(1) per pixel whatever r (overscan borders are tens of pixels wide).
void dilateLine(const uint8_t* in, uint8_t* out, int n, int stride, int r) {
  int count = 0;
  for (int i = 0; i < std::min(r, n); ++i) count += in[i * stride];
  for (int i = 0; i < n; ++i) {
    if (i + r < n) count += in[(i + r) * stride];
    if (i - r - 1 >= 0) count -= in[(i - r - 1) * stride];
    out[i * stride] = count > 0;
  }
}

// Max filter over a (2r+1)^2 window: visible pixels grow by r.
std::vector<uint8_t> dilate(const std::vector<uint8_t>& visible, int w, int h, int r) {
  std::vector<uint8_t> rows(visible.size()), out(visible.size());
  for (int y = 0; y < h; ++y) dilateLine(&visible[size_t(y) * w], &rows[size_t(y) * w], w, 1, r);
  for (int x = 0; x < w; ++x) dilateLine(&rows[x], &out[x], h, w, r);
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

// With overscan, whether a tan-angle is in the field the panel shows (beyond it the panel
// shows the field's edge).
bool inShownField(const EyeBufferSpec& s, const glm::dvec2& t) {
  return s.overscan <= 0.0 || (t.x >= -s.field.left && t.x <= s.field.right &&
                               t.y >= -s.field.down && t.y <= s.field.up);
}

// 1 where some channel of the lens shows the pixel's centre at this pose, with no margin.
std::vector<uint8_t> lensVisible(const LensModel& m, const EyeBufferSpec& s) {
  std::vector<uint8_t> visible(size_t(s.width) * s.height);
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const glm::dvec2 t = pixelCentreTan(s, x, y);
      visible[size_t(y) * s.width + x] = inShownField(s, t) && anyChannelSeen(m, s, t);
    }
  return visible;
}

// How far, in pixels, a head turn of 'overscan' can move a pixel whose direction is at
// tan-radius rho. The tan-plane is a gnomonic projection: a direction at angle a = atan(rho)
// from the axis moves by at most tan(a + turn) - rho, radially, when it turns.
int turnReachPixels(const EyeBufferSpec& s, double rho) {
  const double pixelsPerTan = std::max(s.width / double(s.fov.left + s.fov.right),
                                       s.height / double(s.fov.up + s.fov.down));
  return int(std::ceil(pixelsPerTan * (std::tan(std::atan(rho) + s.overscan) - rho)));
}

// Adds every pixel whose direction is within 'overscan' of a visible pixel's: what a head
// turned by up to that angle brings into the lens. The nearest visible direction of a pixel
// outside the set is on the set's boundary, so each boundary pixel marks the pixels within
// the angle around it (a small ellipse in the tan-plane, searched in its bounding square).
std::vector<uint8_t> growByTurn(const EyeBufferSpec& s, const std::vector<uint8_t>& visible) {
  const int w = s.width, h = s.height;
  std::vector<glm::vec3> dir(visible.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      dir[size_t(y) * w + x] = glm::normalize(glm::vec3(glm::vec2(pixelCentreTan(s, x, y)), -1.0f));
  const float cosTurn = float(std::cos(s.overscan));
  const auto seen = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < w && y < h && visible[size_t(y) * w + x];
  };
  std::vector<uint8_t> out = visible;
  for (int qy = 0; qy < h; ++qy)
    for (int qx = 0; qx < w; ++qx) {
      if (!seen(qx, qy) ||
          (seen(qx - 1, qy) && seen(qx + 1, qy) && seen(qx, qy - 1) && seen(qx, qy + 1)))
        continue;  // not on the boundary
      const glm::vec3 dq = dir[size_t(qy) * w + qx];
      const int r = turnReachPixels(s, glm::length(glm::vec2(dq) / -dq.z)) + 1;
      for (int y = std::max(0, qy - r); y <= std::min(h - 1, qy + r); ++y)
        for (int x = std::max(0, qx - r); x <= std::min(w - 1, qx + r); ++x) {
          const size_t i = size_t(y) * w + x;
          if (!out[i] && glm::dot(dir[i], dq) >= cosTurn) out[i] = 1;
        }
    }
  return out;
}

}  // namespace

std::vector<uint8_t> hiddenAreaMask(const LensModel& m, const EyeBufferSpec& s, int r) {
  std::vector<uint8_t> visible = lensVisible(m, s);
  if (s.overscan > 0.0) visible = growByTurn(s, visible);
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
  const std::vector<uint8_t> seen = s.overscan > 0.0 ? lensVisible(m, s) : std::vector<uint8_t>();
  // Eye-buffer pixels per tan-angle area: constant over the buffer.
  const double bufferPixelsPerTanArea =
      s.width * s.height / (double(s.fov.left + s.fov.right) * (s.fov.up + s.fov.down));
  std::vector<float> density(hidden.size(), 0.0f);
  float lowest = std::numeric_limits<float>::max();
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const size_t i = size_t(y) * s.width + x;
      if (hidden[i] || (!seen.empty() && !seen[i])) continue;
      const glm::dvec2 screen = tanToScreen(m, s.eye, pixelCentreTan(s, x, y));
      density[i] = float(displayPixelsPerTanArea(m, s.eye, screen) / bufferPixelsPerTanArea);
      lowest = std::min(lowest, density[i]);
    }
  // Overscan pixels: shown only after a turn, at the periphery, where the density is lowest.
  for (size_t i = 0; i < seen.size(); ++i)
    if (!hidden[i] && !seen[i]) density[i] = lowest;
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
