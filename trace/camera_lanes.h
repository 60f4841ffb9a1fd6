// core/camera.h's CameraRays::pixelRay for a run of pixels, eight at a time in SIMD lanes
// (trace/lanes.h): the same bits as the scalar call. One division per coordinate, a
// square root and a division for the normalisation made each scalar ray a chain the divider
// could not overlap (CameraRays::direction and the wait on it were ~5 % of a reusing eye's
// time, perf annotate); eight lanes share one vector division.
#pragma once

#include <cstddef>
#include <span>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/camera.h"

namespace photovr {

// out[i - begin] = rays.pixelRay(x, y) for the pixels i in [begin, begin + out.size()) of the
// row-major image rays describes (x = i % width, y = i / width).
void pixelRays(const CameraRays& rays, size_t begin, std::span<glm::vec3> out);
// out[k] = rays.direction(samples[k].x, samples[k].y): rays through samples at window
// coordinates (pt's primary rays, one per sample position).
void sampleRays(const CameraRays& rays, std::span<const glm::vec2> samples,
                std::span<glm::vec3> out);

}  // namespace photovr
