// The camera's rays in lanes (trace/camera_lanes.h) are CameraRays::pixelRay's, bit for bit,
// for any run of pixels: the hybrid's hit rebuild takes them in its place.
#include "trace/camera_lanes.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "tests/trace/trace_test_util.h"

namespace photovr {
namespace {

bool sameBits(const glm::vec3& a, const glm::vec3& b) {
  return std::memcmp(&a, &b, sizeof(glm::vec3)) == 0;
}

// Cameras turned any way (trace_test_util.h).
EyeCamera randomCamera(std::mt19937& rng) {
  return testing::randomEyeCamera(rng, 0.0f);
}

TEST(CameraLanes, GiveThePixelRaysBitForBit) {
  std::mt19937 rng(7);
  for (int k = 0; k < 20; ++k) {
    const EyeCamera cam = randomCamera(rng);
    const CameraRays rays(cam);
    const size_t n = size_t(cam.width) * cam.height;
    const size_t begin = rng() % n, count = 1 + rng() % (n - begin);
    std::vector<glm::vec3> lanes(count);
    pixelRays(rays, begin, lanes);
    for (size_t i = begin; i < begin + count; ++i) {
      const int x = int(i % size_t(cam.width)), y = int(i / size_t(cam.width));
      const glm::vec3 scalar = rays.pixelRay(x, y);
      ASSERT_TRUE(sameBits(lanes[i - begin], scalar))
          << "camera " << k << ", pixel (" << x << ", " << y << "): " << lanes[i - begin].x << ' '
          << lanes[i - begin].y << ' ' << lanes[i - begin].z << " against " << scalar.x << ' '
          << scalar.y << ' ' << scalar.z;
    }
  }
}

TEST(CameraLanes, GiveTheSampleRaysBitForBit) {
  std::mt19937 rng(11);
  for (int k = 0; k < 20; ++k) {
    const EyeCamera cam = randomCamera(rng);
    const CameraRays rays(cam);
    // Anywhere in the window and a little outside it (pt's samples reach +-0.5 px past).
    std::uniform_real_distribution<float> px(-1.0f, cam.width + 1.0f), py(-1.0f, cam.height + 1.0f);
    std::vector<glm::vec2> samples(1 + rng() % 100);
    for (glm::vec2& s : samples) s = {px(rng), py(rng)};
    std::vector<glm::vec3> lanes(samples.size());
    sampleRays(rays, samples, lanes);
    for (size_t i = 0; i < samples.size(); ++i)
      ASSERT_TRUE(sameBits(lanes[i], rays.direction(samples[i].x, samples[i].y)))
          << "camera " << k << ", sample " << i;
  }
}

TEST(CameraLanes, AWholeImageMatchesTheEyeCamera) {
  EyeCamera cam;
  cam.width = 64, cam.height = 72;
  cam.fov = FovTangents::dk2LeftEye();
  cam.jitter = glm::vec2(0.25f, -0.125f);
  const CameraRays rays(cam);
  std::vector<glm::vec3> lanes(size_t(cam.width) * cam.height);
  pixelRays(rays, 0, lanes);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      ASSERT_TRUE(sameBits(lanes[size_t(y) * cam.width + x], cam.pixelRay(x, y)))
          << "pixel (" << x << ", " << y << ")";
}

}  // namespace
}  // namespace photovr
