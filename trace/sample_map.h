// Per-pixel sample counts of one eye: uniform (every pixel gets the frame's samples per
// pixel) or one count per pixel, rows bottom-up as the G-buffer (a lens-matched density, or
// a hidden-area mask where 0 = not traced). Built by hybrid/sample_maps.h from the lens.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace photovr {

class SampleMap {
 public:
  SampleMap() = default;  // uniform
  explicit SampleMap(std::vector<uint16_t> perPixel) : perPixel_(std::move(perPixel)) {}

  bool isUniform() const { return perPixel_.empty(); }
  // Samples of 'pixel' when the frame asks for 'uniformSpp' per pixel.
  uint32_t samplesAt(size_t pixel, uint32_t uniformSpp) const {
    return isUniform() ? uniformSpp : perPixel_[pixel];
  }
  // True when the pixel is never traced (only a per-pixel map has such pixels).
  bool skips(size_t pixel) const { return !isUniform() && perPixel_[pixel] == 0; }
  const std::vector<uint16_t>& perPixel() const { return perPixel_; }

 private:
  std::vector<uint16_t> perPixel_;
};

using StereoSampleMaps = std::array<SampleMap, 2>;  // per eye; default: both uniform

}  // namespace photovr
