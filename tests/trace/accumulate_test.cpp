// render's accumulation of frames (trace/trace_output.h), which runs over the cores in
// ranges (core/parallel_ranges.h): every pixel of every plane is the running mean a serial
// loop computes, to the bit, and that is the frames' mean to float rounding.
#include "trace/trace_output.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <random>
#include <vector>

namespace photovr {
namespace {

// More pixels than a few ranges hold (kRangeGrain 4096), and not a multiple of one.
constexpr int kW = 131, kH = 97;
constexpr int kFrames = 7;

std::vector<glm::vec3> randomPlane(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 4.0f);
  std::vector<glm::vec3> v(size_t(kW) * kH);
  for (glm::vec3& x : v) x = glm::vec3(u(rng), u(rng), u(rng));
  return v;
}

EyeImage randomFrame(std::mt19937& rng) {
  EyeImage f;
  f.width = kW;
  f.height = kH;
  f.color = randomPlane(rng);
  f.albedo = randomPlane(rng);
  f.normal = randomPlane(rng);
  f.diffuse = randomPlane(rng);
  f.specular = randomPlane(rng);
  f.diffuseAlbedo = randomPlane(rng);
  f.specularAlbedo = randomPlane(rng);
  f.guide = randomPlane(rng);
  f.depth.assign(f.color.size(), 0.5f);
  std::uniform_int_distribution<uint32_t> spp(0, 4);
  f.samples.resize(f.color.size());
  for (uint32_t& s : f.samples) s = spp(rng);
  f.rays = 1000;
  return f;
}

// The planes accumulate must average, listed here, not taken from kAveragedPlanes: a plane
// dropped from that list must fail this test.
using Plane = std::vector<glm::vec3> EyeImage::*;
constexpr Plane kMeanPlanes[] = {&EyeImage::color,         &EyeImage::albedo,
                                 &EyeImage::diffuse,       &EyeImage::specular,
                                 &EyeImage::diffuseAlbedo, &EyeImage::specularAlbedo};

TEST(Accumulate, EveryPixelIsTheSerialRunningMeanAndTheFramesMean) {
  std::mt19937 rng(7);
  std::vector<EyeImage> frames;
  for (int f = 0; f < kFrames; ++f) frames.push_back(randomFrame(rng));
  EyeImage sum;
  for (int f = 0; f < kFrames; ++f) accumulate(sum, frames[size_t(f)], f);

  const size_t n = size_t(kW) * kH;
  for (Plane plane : kMeanPlanes) {
    size_t differing = 0, offMean = 0;
    for (size_t i = 0; i < n; ++i) {
      glm::vec3 serial = (frames[0].*plane)[i], mean(0.0f);
      for (int f = 1; f < kFrames; ++f)
        serial += ((frames[size_t(f)].*plane)[i] - serial) * (1.0f / float(f + 1));
      for (const EyeImage& f : frames) mean += (f.*plane)[i];
      mean /= float(kFrames);
      differing += (sum.*plane)[i] != serial;
      // The running mean's rounding: each of the kFrames steps rounds a subtraction, a
      // product and a sum of values below 4, a few ulps of 4 each.
      const float tolerance = 4.0f * 4.0f * kFrames * FLT_EPSILON;
      for (int k = 0; k < 3; ++k) offMean += std::abs((sum.*plane)[i][k] - mean[k]) > tolerance;
    }
    EXPECT_EQ(differing, 0u) << "pixels that differ from the serial loop's bits";
    EXPECT_EQ(offMean, 0u) << "values further from the frames' mean than rounding explains";
  }
  size_t wrongCounts = 0;
  for (size_t i = 0; i < n; ++i) {
    uint32_t total = 0;
    for (const EyeImage& f : frames) total += f.samples[i];
    wrongCounts += sum.samples[i] != total;
  }
  EXPECT_EQ(wrongCounts, 0u) << "pixels whose sample counts do not sum";
  EXPECT_EQ(sum.rays, uint64_t(kFrames) * 1000u);
  // Depth, normal and guide are the first frame's: frames share their view.
  EXPECT_EQ(sum.normal, frames[0].normal);
  EXPECT_EQ(sum.depth, frames[0].depth);
}

}  // namespace
}  // namespace photovr
