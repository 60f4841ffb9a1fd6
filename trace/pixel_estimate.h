// One pixel's samples and how they are stored: shared by the pure path tracer and the
// hybrid so both produce the same outputs from the same estimate.
#pragma once

#include <cstdint>

#include <glm/vec4.hpp>

#include "trace/path_tracer.h"

namespace photovr {

// Sums over a pixel's samples. A sample either continues a path from its primary hit or
// (pure path tracing) missed every surface and saw the environment.
struct alignas(16) PixelEstimate {
  // Provided: with the implicit one, GCC zeroed the estimate with `rep stosq`, from which
  // the first addPath's loads cannot forward (half of addPath's time, perf annotate).
  PixelEstimate() {}

  // The sums are 16-byte lanes (the fourth 0), each written and read whole: as vec3s they
  // lay across the initialisers' 16-byte stores and addPath's 8- and 4-byte ones, and each
  // read of one waited for store forwarding to fail (two fifths of addPath's time in the
  // reusing eye's profile, about half of it after; storePixel's hot spot is its divisions;
  // docs/MEASUREMENTS.md, "pt's reusing eye").
  glm::vec4 diffuse{0.0f}, specular{0.0f}, albedo{0.0f};
  glm::vec4 emitted{0.0f};  // what the primary rays saw themselves: emission, environment
  glm::vec4 diffuseAlbedo{0.0f}, specularAlbedo{0.0f};  // demodulation albedos (clamped)
  glm::vec3 guide{0.0f};                                // the first path's PathResult::guide
  uint32_t samples = 0;                                 // paths continued from a hit
  uint32_t misses = 0;                                  // primary rays that left the scene
  uint64_t rays = 0, rejected = 0, ownBounces = 0;
};

// Albedos are clamped to this before demodulating, and the same clamped value is stored,
// so remodulation (radiance = demodulated x stored albedo) is exact (SVGF sec. 4.1).
constexpr float kMinDemodulationAlbedo = 1e-3f;

// One path continued from a hit whose emission towards the eye is 'emission' (its result
// 'r', which carries its demodulation albedos).
void addPath(PixelEstimate& e, const glm::vec3& emission, const PathResult& r);

// A primary ray that left the scene and saw 'environment'.
void addMissedRay(PixelEstimate& e, const glm::vec3& environment);

// Writes colour (the mean over every sample, emission and environment included), the
// demodulated lobes and their albedos (means over the samples that hit), the albedo AOV,
// the guide and the count of paths at pixel i: every plane of the image but depth and
// normal, which are the hit's (the caller's to write). A pixel with no path has samples 0,
// its lobes, albedos, albedo and guide 0 (a hidden-area pixel, or pure path tracing's
// background, whose colour is then the environment it saw).
void storePixel(EyeImage& image, size_t i, const PixelEstimate& estimate);

// The same for a pixel that traces nothing: colour 'color' (the environment a sky pixel
// shows, or 0), samples 0, the rest 0 but depth and normal.
void storeUntracedPixel(EyeImage& image, size_t i, const glm::vec3& color);

// Sizes every buffer of the image, keeping what an earlier frame left (recycled storage,
// docs/ARCHITECTURE.md, "Memory reuse"; new storage is zero): a tracer writes every pixel's
// every plane itself, in its parallel pass, where zeroing the image first was a serial pass
// over all of it (104 bytes a pixel: ~4.5 ms an eye at 960x1080 here, outside every stage
// timer).
void sizeEyeImage(EyeImage& image, int width, int height);

// Sizes every buffer of the image (zeros).
void allocateEyeImage(EyeImage& image, int width, int height);

}  // namespace photovr
