#include "app/gbuffer_output.h"

#include <algorithm>
#include <cmath>

namespace photovr::app {
namespace {

constexpr uint32_t kNoHit = kNoHitInstance;

template <typename F>
Image8 colourImage(const gl::GBufferImage& g, F pixel) {
  Image8 out(g.width, g.height, 3);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const size_t i = g.index(x, g.height - 1 - y);
      const glm::u8vec3 c = g.visibility[i].x == kNoHit ? glm::u8vec3(0) : pixel(i);
      uint8_t* d = out.at(x, y);
      d[0] = c.r, d[1] = c.g, d[2] = c.b;
    }
  return out;
}

uint8_t unorm8(float v) {
  return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

// Well-spread colours for consecutive ids (a 32-bit integer hash, "lowbias32" by
// C. Wellons, 2018).
glm::u8vec3 hashColour(uint32_t id) {
  uint32_t h = id + 0x9e3779b9u;
  h ^= h >> 16, h *= 0x7feb352du, h ^= h >> 15, h *= 0x846ca68bu, h ^= h >> 16;
  return glm::u8vec3(64 + (h & 0xBF), 64 + ((h >> 8) & 0xBF), 64 + ((h >> 16) & 0xBF));
}

void blitHalf(const Image8& src, Image8& dst, int ox, int oy) {
  for (int y = 0; y < src.height / 2; ++y)
    for (int x = 0; x < src.width / 2; ++x)
      for (int c = 0; c < 3; ++c) {
        const int sum = src.data[((2 * y) * src.width + 2 * x) * 3 + c] +
                        src.data[((2 * y) * src.width + 2 * x + 1) * 3 + c] +
                        src.data[((2 * y + 1) * src.width + 2 * x) * 3 + c] +
                        src.data[((2 * y + 1) * src.width + 2 * x + 1) * 3 + c];
        dst.at(ox + x, oy + y)[c] = uint8_t((sum + 2) / 4);
      }
}

}  // namespace

ImageF depthImage(const gl::GBufferImage& g) {
  ImageF out(g.width, g.height, 1);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) *out.at(x, y) = g.depth[g.index(x, g.height - 1 - y)];
  return out;
}

Image8 normalImage(const gl::GBufferImage& g) {
  return colourImage(g, [&](size_t i) {
    const glm::vec3 n = glm::vec3(g.normal[i]) * 0.5f + 0.5f;
    return glm::u8vec3(unorm8(n.x), unorm8(n.y), unorm8(n.z));
  });
}

Image8 albedoImage(const gl::GBufferImage& g) {
  return colourImage(g, [&](size_t i) {
    const glm::vec4 c = g.baseColor[i];
    return glm::u8vec3(toSrgb8(c.r), toSrgb8(c.g), toSrgb8(c.b));
  });
}

Image8 idImage(const gl::GBufferImage& g) {
  return colourImage(g, [&](size_t i) { return hashColour(g.visibility[i].x); });
}

Image8 depthPreview(const gl::GBufferImage& g) {
  float lo = 1.0f, hi = 0.0f;
  for (size_t i = 0; i < g.depth.size(); ++i)
    if (g.visibility[i].x != kNoHit) lo = std::min(lo, g.depth[i]), hi = std::max(hi, g.depth[i]);
  // Reversed-Z depth is ~1/distance: a log scale spreads near and far evenly.
  const float a = std::log(std::max(lo, 1e-12f)), b = std::log(std::max(hi, 1e-12f));
  return colourImage(g, [&](size_t i) {
    const float t = b > a ? (std::log(std::max(g.depth[i], 1e-12f)) - a) / (b - a) : 1.0f;
    const uint8_t v = unorm8(0.15f + 0.85f * t);
    return glm::u8vec3(v, v, v);
  });
}

Image8 gbufferMosaic(const gl::GBufferImage& left, const gl::GBufferImage* right) {
  const int w = left.width / 2 * 2, h = left.height / 2 * 2, eyes = right ? 2 : 1;
  Image8 out(eyes * w, h, 3);
  for (int e = 0; e < eyes; ++e) {
    const gl::GBufferImage& g = e == 0 ? left : *right;
    blitHalf(albedoImage(g), out, e * w, 0);
    blitHalf(normalImage(g), out, e * w + w / 2, 0);
    blitHalf(idImage(g), out, e * w, h / 2);
    blitHalf(depthPreview(g), out, e * w + w / 2, h / 2);
  }
  return out;
}

std::vector<std::string> writeEyeFiles(const gl::GBufferImage& g, const std::string& dir) {
  const std::vector<std::string> paths = {dir + "/depth.exr", dir + "/normal.png",
                                          dir + "/albedo.png", dir + "/ids.png"};
  writeImage(paths[0], depthImage(g));
  writeImage(paths[1], normalImage(g));
  writeImage(paths[2], albedoImage(g));
  writeImage(paths[3], idImage(g));
  return paths;
}

}  // namespace photovr::app
