// The numerical stress suite (issue 7): scenes where renderers usually break — far from the
// origin, extreme scales, grazing angles, roughness and metallic at 0 and 1, degenerate and
// duplicate triangles, denormal vertex data, a tiny extremely bright light, coincident
// surfaces. Each case renders hybrid and pt and checks: no NaN/Inf pixel, no rejected
// sample, agreement with a well-conditioned reference version of the same case (acne or
// leaks show up as error), and hybrid/pt agreement.
#pragma once

#include <string>
#include <vector>

namespace photovr {

struct StressResult {
  std::string name;
  size_t nonFinitePixels = 0;
  uint64_t rejectedSamples = 0;
  double relMseVsReference = 0.0;  // the case against its well-conditioned twin
  double relMseHybridVsPt = 0.0;
  double maxRelMse = 0.0;  // the bounds the case must stay under
  double maxHybridVsPt = 0.0;
  bool passed = false;
};

// 'quick' uses smaller images and fewer samples (the test suite); the full run is
// `photovr stress`. Needs a current GL context.
std::vector<StressResult> runStressSuite(bool quick);

std::string formatStressReport(const std::vector<StressResult>& results);

}  // namespace photovr
