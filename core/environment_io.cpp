#include "core/environment_io.h"

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <filesystem>
#include <vector>

#include "core/error.h"
#include "core/image_io.h"

namespace photovr {
namespace {

glm::vec3 rgbAt(const ImageF& image, int x, int y) {
  const float* p = image.at(x, y);
  return image.channels >= 3 ? glm::vec3(p[0], p[1], p[2]) : glm::vec3(p[0]);
}

// Lossy EXR codecs (DWAA/DWAB: 8x8 DCT blocks; B44: 4x4 blocks inside them) leave small
// negatives where a map clamped to 0 was compressed: their error is a fraction of the
// block's values. Measured on a test map (tests/core/environment_io_test.cpp), DWAA/DWAB at
// OpenEXR's default level 45 and B44: at most 1.25 % of the largest value of that channel
// in the pixel's aligned 8x8 block. A negative up to 1/16 of it (5x that) is codec error
// and clamped to 0; beyond, it is a broken map (a sign error, a subtraction gone wrong
// gives values comparable to their neighbours') and stays an error, as NaN and inf do.
constexpr int kCodecBlock = 8;
constexpr float kCodecErrorFraction = 1.0f / 16.0f;

// The largest value of each channel per aligned kCodecBlock x kCodecBlock block.
std::vector<glm::vec3> blockMaxima(const ImageF& image) {
  const int bw = (image.width + kCodecBlock - 1) / kCodecBlock;
  const int bh = (image.height + kCodecBlock - 1) / kCodecBlock;
  std::vector<glm::vec3> maxima(size_t(bw) * bh, glm::vec3(0.0f));
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      glm::vec3& m = maxima[size_t(y / kCodecBlock) * bw + x / kCodecBlock];
      m = glm::max(m, rgbAt(image, x, y));  // NaN is caught per pixel below
    }
  return maxima;
}

bool isFiniteRgb(const glm::vec3& c) {
  return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z);
}

std::string shortNumber(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", double(v));
  return text;
}

// Small negatives clamped to 0, counted.
struct Clamped {
  size_t count = 0;
  float mostNegative = 0.0f;
};

std::string describe(const glm::vec3& c) {
  return "(" + std::to_string(c.x) + ", " + std::to_string(c.y) + ", " + std::to_string(c.z) + ")";
}

// OpenImageIO's error text can span lines; the error policy wants one.
ImageF readOneLineErrors(const std::string& path) {
  try {
    return readImageF(path);
  } catch (const InputError& e) {
    const std::string what = e.what();
    throw InputError("", what.substr(0, what.find('\n')));
  }
}

}  // namespace

Environment loadEnvironment(const std::string& path, std::string* warning) {
  const ImageF image = readOneLineErrors(path);
  Environment env;
  env.type = Environment::Type::Map;
  env.name = std::filesystem::path(path).filename().string();
  env.width = image.width;
  env.height = image.height;
  env.pixels.resize(size_t(image.width) * image.height);
  const std::vector<glm::vec3> maxima = blockMaxima(image);
  const int blocksPerRow = (image.width + kCodecBlock - 1) / kCodecBlock;
  Clamped clamped;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const glm::vec3 read = rgbAt(image, x, y);
      glm::vec3 c = read;
      const glm::vec3& m = maxima[size_t(y / kCodecBlock) * blocksPerRow + x / kCodecBlock];
      for (int k = 0; k < 3 && isFiniteRgb(c); ++k) {
        if (c[k] >= 0.0f || -c[k] > kCodecErrorFraction * m[k]) continue;
        ++clamped.count;
        clamped.mostNegative = std::min(clamped.mostNegative, c[k]);
        c[k] = 0.0f;
      }
      if (!isFiniteRgb(c) || glm::any(glm::lessThan(c, glm::vec3(0.0f))))
        throw InputError(path, "pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                   ") is negative or not finite " + describe(read) +
                                   "; radiance must be finite and >= 0 (negatives up to 1/16 of "
                                   "their 8x8 block's largest value are taken as lossy-codec "
                                   "error and clamped)");
      env.pixels[size_t(y) * image.width + x] = c;
    }
  if (!warning) return env;
  std::vector<std::string> notes;
  if (clamped.count > 0)
    notes.push_back("clamped " + std::to_string(clamped.count) +
                    " small negative values to 0 (lossy compression leaves them; most negative " +
                    shortNumber(clamped.mostNegative) + ")");
  // Equirectangular maps span 360 x 180 degrees; another aspect means texels are stretched.
  if (image.width != 2 * image.height)
    notes.push_back(std::to_string(image.width) + "x" + std::to_string(image.height) +
                    " is not 2:1, stretched to the equirectangular sphere");
  warning->clear();
  for (const std::string& n : notes) *warning += (warning->empty() ? path + ": " : "; ") + n;
  return env;
}

}  // namespace photovr
