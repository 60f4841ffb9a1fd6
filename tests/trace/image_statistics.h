// "The image does not change within Monte Carlo error": two renders of the same expected
// image, each the mean of independent frames, compared region by region with a z-test.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "trace/sampling.h"

namespace photovr::testing {

// Per-pixel mean of frames and the variance of that mean (sample variance / n), on the
// luminance of each pixel.
struct FrameStatistics {
  int width = 0, height = 0, frames = 0;
  std::vector<double> mean, varianceOfMean;
};

inline FrameStatistics statisticsOf(const std::vector<std::vector<glm::vec3>>& frames, int width,
                                    int height) {
  FrameStatistics s{width, height, int(frames.size()), {}, {}};
  const size_t n = size_t(width) * height;
  s.mean.assign(n, 0.0);
  s.varianceOfMean.assign(n, 0.0);
  std::vector<double> sq(n, 0.0);
  for (const auto& f : frames)
    for (size_t i = 0; i < n; ++i) {
      const double l = luminance(f[i]);
      s.mean[i] += l;
      sq[i] += l * l;
    }
  const double k = double(frames.size());
  for (size_t i = 0; i < n; ++i) {
    s.mean[i] /= k;
    s.varianceOfMean[i] = std::max(0.0, (sq[i] - k * s.mean[i] * s.mean[i]) / (k - 1.0)) / k;
  }
  return s;
}

// |difference| / its standard error; a difference with zero variance (sky, black: every
// sample equal) must itself be 0.
inline double zOf(double difference, double varianceOfDifference) {
  if (varianceOfDifference > 0.0) return std::abs(difference) / std::sqrt(varianceOfDifference);
  return std::abs(difference) > 1e-9 ? 1e30 : 0.0;
}

// The largest of z(x0, x1, y0, y1) over the whole image and a regions x regions grid.
template <class RegionZ>
double worstRegion(int width, int height, int regions, const RegionZ& z) {
  double worst = z(0, width, 0, height);
  for (int ry = 0; ry < regions; ++ry)
    for (int rx = 0; rx < regions; ++rx)
      worst = std::max(worst, z(rx * width / regions, (rx + 1) * width / regions,
                                ry * height / regions, (ry + 1) * height / regions));
  return worst;
}

// The largest |z| over a regions x regions grid (and the whole image) of the difference of
// summed luminance, z = (sum a - sum b) / sqrt(sum var_a + sum var_b): pixels are
// independent (counter-based random numbers), so each region's sum is close to normal.
// Pixels with zero variance in both (sky, black) still count: their difference must be 0.
inline double maxRegionZ(const FrameStatistics& a, const FrameStatistics& b, int regions) {
  return worstRegion(a.width, a.height, regions, [&](int x0, int x1, int y0, int y1) {
    double d = 0.0, v = 0.0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const size_t i = size_t(y) * a.width + x;
        d += a.mean[i] - b.mean[i];
        v += a.varianceOfMean[i] + b.varianceOfMean[i];
      }
    return zOf(d, v);
  });
}

// The same test on paired frames: frame k of 'a' and frame k of 'b' draw the same numbers
// (one seed, one frame index), so their difference is far less noisy than either. Each
// region's per-frame difference of summed luminance, D_k, is one sample; z = mean D /
// sqrt(var D / K) with the sample variance over the K frames, as the test above treats frames
// as independent. A region whose frames all agree (D_k = 0: sky, black) must have mean 0.
inline double maxPairedRegionZ(const std::vector<std::vector<glm::vec3>>& a,
                               const std::vector<std::vector<glm::vec3>>& b, int width, int height,
                               int regions) {
  const size_t frames = std::min(a.size(), b.size());
  return worstRegion(width, height, regions, [&](int x0, int x1, int y0, int y1) {
    double sum = 0.0, sq = 0.0;
    for (size_t k = 0; k < frames; ++k) {
      double d = 0.0;
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          const size_t i = size_t(y) * width + x;
          d += double(luminance(a[k][i])) - double(luminance(b[k][i]));
        }
      sum += d, sq += d * d;
    }
    const double n = double(frames), mean = sum / n;
    return zOf(mean, std::max(0.0, (sq - n * mean * mean) / (n - 1.0)) / n);
  });
}

// 4 x 4 regions + the whole image = 17 two-sided tests; |z| < 4 for all of them has a
// false-alarm rate of 17 x 6.3e-5 = 1e-3 under the normal approximation.
constexpr int kRegions = 4;
constexpr double kMaxZ = 4.0;

}  // namespace photovr::testing
