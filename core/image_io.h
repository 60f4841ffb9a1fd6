// Image files through OpenImageIO. Writes are atomic: the file is written next to its
// destination under a temporary name and renamed, so a failed write leaves nothing
// half-written. Errors throw InputError naming the file.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace photovr {

struct ImageF {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<float> data;  // row-major, row 0 at the top, interleaved channels
  ImageF() = default;
  ImageF(int w, int h, int c) : width(w), height(h), channels(c), data(size_t(w) * h * c, 0.f) {}
  float* at(int x, int y) { return &data[(size_t(y) * width + x) * channels]; }
  const float* at(int x, int y) const { return &data[(size_t(y) * width + x) * channels]; }
};

struct Image8 {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<uint8_t> data;
  Image8() = default;
  Image8(int w, int h, int c) : width(w), height(h), channels(c), data(size_t(w) * h * c, 0) {}
  uint8_t* at(int x, int y) { return &data[(size_t(y) * width + x) * channels]; }
};

// Linear float image; .exr (half-free 32-bit float) or .hdr by extension.
void writeImage(const std::string& path, const ImageF& image);
// 8-bit image (already encoded, e.g. sRGB); .png.
void writeImage(const std::string& path, const Image8& image);

// A file of a command's output: its path, and what writes it there (making its pixels in
// the same call, so that only the files being written hold theirs).
struct OutputFile {
  std::string path;
  std::function<void(const std::string& path)> write;
};

// Writes the files concurrently, each one atomically (writeImage). A render's ~20 images
// (compressed EXR, PNG) had taken ~2 s of `photovr render`'s ~6 at 960x1080 one after
// another (docs/MEASUREMENTS.md, "Serial passes left in the frame"). If any fails, the
// others are still written and the first failure in list order is thrown: the error does
// not depend on which thread got there first.
void writeFiles(const std::vector<OutputFile>& files);

// Reads any format OpenImageIO knows as float (linear values as stored in the file).
ImageF readImageF(const std::string& path);
// Reads an 8-bit image, expanded to RGBA.
Image8 readImageRGBA8(const std::string& path);

// RGBA8 rows bottom-up (as GL reads them back) to a top-down RGB image.
Image8 flipToImage(const std::vector<glm::u8vec4>& pixels, int width, int height);

// sRGB transfer function (IEC 61966-2-1).
float linearToSrgb(float linear);
float srgbToLinear(float encoded);
uint8_t toSrgb8(float linear);  // clamps to [0, 1] first

}  // namespace photovr
