#include "trace/convergence.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "core/error_metrics.h"
#include "core/parallel_ranges.h"

namespace photovr {

void ConvergenceMonitor::add(int eye, const std::vector<glm::vec3>& color, int width) {
  if (eye < 0 || width <= 0 || color.size() % size_t(width) != 0)
    throw std::invalid_argument("ConvergenceMonitor: bad eye or frame size");
  if (size_t(eye) >= eyes_.size()) eyes_.resize(size_t(eye) + 1);
  Eye& e = eyes_[size_t(eye)];
  if (e.frames == 0) {
    e.sum.assign(color.size(), glm::dvec3(0.0));
    e.sumSquares.assign(color.size(), glm::dvec3(0.0));
    e.width = width;
  }
  if (color.size() != e.sum.size() || width != e.width)
    throw std::invalid_argument("ConvergenceMonitor: frame size changed");
  parallelRanges(color.size(), [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const glm::dvec3 c(color[i]);
      e.sum[i] += c;
      e.sumSquares[i] += c * c;
    }
  });
  ++e.frames;
}

int ConvergenceMonitor::frames(int eye) const {
  return eye >= 0 && size_t(eye) < eyes_.size() ? eyes_[size_t(eye)].frames : 0;
}

double ConvergenceMonitor::relativeVariance(const Eye& e, size_t& values) {
  const double n = e.frames;
  const int w = e.width, h = int(e.sum.size() / size_t(w));
  double total = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      glm::dvec3 box(0.0);
      int count = 0;
      for (int yy = std::max(0, y - 1); yy <= std::min(h - 1, y + 1); ++yy)
        for (int xx = std::max(0, x - 1); xx <= std::min(w - 1, x + 1); ++xx, ++count)
          box += e.sum[size_t(yy) * w + xx];
      box /= n * count;
      const size_t i = size_t(y) * w + x;
      for (int k = 0; k < 3; ++k) {
        const double mean = e.sum[i][k] / n;
        // Unbiased sample variance; clamped at 0 against rounding of equal frames.
        const double var = std::max(0.0, (e.sumSquares[i][k] - n * mean * mean) / (n - 1.0));
        total += var / n / (box[k] * box[k] + kRelMseEpsilon);
        ++values;
      }
    }
  return total;
}

double ConvergenceMonitor::estimatedRelMse() const {
  double total = 0.0;
  size_t values = 0;
  for (const Eye& e : eyes_) {
    if (e.frames < kMinFrames) return std::numeric_limits<double>::infinity();
    total += relativeVariance(e, values);
  }
  return values ? total / double(values) : std::numeric_limits<double>::infinity();
}

}  // namespace photovr
