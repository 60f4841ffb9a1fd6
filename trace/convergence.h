// When a static view has converged: an estimate of the error of the accumulated mean from
// the frames themselves, so accumulation can stop tracing and keep presenting (issue 7,
// item 3, "converged accumulation").
//
// Frames of a static camera are independent estimates of the same image, so per pixel and
// channel the sample variance s^2 of the frame values over n frames gives the variance of
// their mean, s^2 / n. The estimate is that variance in the units of relMse
// (core/error_metrics.h): mean over pixels and channels of (s^2 / n) / (m^2 + eps), with
// m the running mean box-filtered over 3 x 3 pixels in place of the reference. Filtered,
// because a firefly inflates a pixel's s^2 and its own m^2 together and the ratio would hide
// it: unfiltered, the estimate came out 2.7x below the measured relMSE of a 32-frame
// 24 x 27 cornell render (0.019 vs 0.052); filtered, 1.3x below (0.039), within the test's
// factor 1.5 (tests/trace/convergence_test.cpp). Still optimistic on firefly-prone scenes:
// choose a --converge threshold with that in mind.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace photovr {

class ConvergenceMonitor {
 public:
  // Adds one frame's colour of one view (eye), 'width' pixels per row; every frame of an eye
  // has the same size.
  void add(int eye, const std::vector<glm::vec3>& color, int width);
  // Frames added to 'eye'.
  int frames(int eye) const;
  // The estimated relMSE of the accumulated mean over every eye; infinity with fewer than
  // kMinFrames frames per eye (a variance from 2 or 3 values is too noisy to stop on).
  double estimatedRelMse() const;
  bool converged(double threshold) const { return estimatedRelMse() < threshold; }

  static constexpr int kMinFrames = 4;

 private:
  struct Eye {
    int frames = 0, width = 0;
    std::vector<glm::dvec3> sum, sumSquares;
  };
  std::vector<Eye> eyes_;
  static double relativeVariance(const Eye& e, size_t& values);
};

}  // namespace photovr
