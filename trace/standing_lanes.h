// Stereo reuse's standing pixels (trace/stereo_reuse.h, standingPixelOf) for a run of right
// samples, eight at a time in SIMD lanes (trace/lanes.h): the scalar function's answers, to
// the bit. It was ~4 % of the reusing eye's time, one pixel at a time: a projection with
// three divisions and a 3x3 matrix per pixel.
#pragma once

#include <span>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "trace/stereo_reuse.h"

namespace photovr {

// One right sample: its primary hit and the ray through its pixel's centre (RightSample's
// centreRay); 'out' receives standingPixelOf(left, *hit, {eye, centreRay, offset, 0}).
struct StandingJob {
  const SurfaceHit* hit;
  glm::vec3 centreRay;
  StandingPixel* out;
};
void standingPixelsOf(const EyeWindow& left, const glm::vec3& eye, const glm::vec2& offset,
                      std::span<const StandingJob> jobs);

}  // namespace photovr
