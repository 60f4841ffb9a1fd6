// One pixel's samples from a primary hit, and how they are stored: shared by the pure path
// tracer and the hybrid so both produce the same outputs from the same estimate.
#pragma once

#include <cstdint>

#include "trace/path_tracer.h"

namespace photovr {

struct PixelEstimate {
  glm::vec3 diffuse{0.0f}, specular{0.0f}, albedo{0.0f};  // sums over the samples
  uint32_t samples = 0;
  uint64_t rays = 0, rejected = 0;
};

// 'spp' paths continued from 'hit', seen along the primary direction 'dir'.
PixelEstimate estimatePixel(const TraceContext& ctx, const SurfaceHit& hit, const glm::vec3& dir,
                            SampleCounters counters, uint32_t spp);

// Albedos are clamped to this before demodulating, and the same clamped value is stored,
// so remodulation (radiance = demodulated x stored albedo) is exact (SVGF sec. 4.1).
constexpr float kMinDemodulationAlbedo = 1e-3f;

// Writes colour (mean + the hit's emission), the demodulated lobes and their albedos, the
// albedo AOV and the sample count at pixel i. Does nothing to the colour when no samples
// were taken (a hidden-area pixel).
void storePixel(EyeImage& image, size_t i, const SurfaceHit& hit, const glm::vec3& dir,
                const PixelEstimate& estimate);

// Sizes every buffer of the image (zeros).
void allocateEyeImage(EyeImage& image, int width, int height);

}  // namespace photovr
