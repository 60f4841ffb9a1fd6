// Pure path tracing places every sample at its own position in the pixel (issue 18): one
// frame of N samples antialiases an edge as N frames of one do, with the sampler's
// stratified positions. Until then all N samples of a frame shared the frame's jitter, and
// a pixel on an edge was all in or all out.
#include <gtest/gtest.h>

#include "tests/trace/trace_test_util.h"
#include "trace/path_tracer.h"

namespace photovr {
namespace {

constexpr int kSize = 8;
constexpr float kEdgeX = 3.3f;  // window x of the emitter's left edge, inside column 3

EyeCamera camera() {
  EyeCamera c;
  c.fov = FovTangents::symmetric(0.8f, 1.0f);
  c.width = c.height = kSize;
  return c;  // at the origin, looking down -Z
}

// A black emitter of radiance 1 on the plane z = -1, its left edge where the ray through
// window x = kEdgeX meets the plane (a vertical line on screen: the camera looks along -Z
// unrotated), reaching far beyond the frame on every other side. Nothing else: a pixel's
// value is exactly the fraction of its samples that hit the emitter.
Scene halfCoveredView() {
  const glm::vec3 d = camera().rayDirection(kEdgeX, 0.5f * kSize);
  const float edge = d.x / -d.z;
  Material emitter = testing::diffuseMaterial(glm::vec3(0.0f));
  emitter.emissiveFactor = glm::vec3(1.0f);
  Scene s;
  s.materials.push_back(emitter);
  testing::addSquare(s, 50.0f, 0, glm::translate(glm::mat4(1.0f), {edge + 50.0f, 0.0f, -1.0f}));
  return s;
}

struct Renderer {
  Scene scene = halfCoveredView();
  EmbreeScene embree{scene};
  LightSet lights{scene};

  EyeImage render(SamplerKind kind, int spp, uint32_t frame) const {
    TraceSettings settings;
    settings.samplesPerPixel = spp;
    settings.sampler = kind;
    settings.maxBounces = 0;
    return renderPathTraced({scene, embree, lights, settings}, camera(), 0, frame);
  }
};

class Antialiasing : public ::testing::TestWithParam<SamplerKind> {};

TEST_P(Antialiasing, OneFrameOfManySamplesCoversTheEdgeByArea) {
  const Renderer r;
  const EyeImage img = r.render(GetParam(), 64, 0);
  for (int y = 0; y < kSize; ++y) {
    // 64 positions stratified in x: Sobol's first 64 points and Halton's 64 from index 1
    // put at most 1 (Sobol, a (0, 6)-net) or 2 (Halton's block starts off the aligned one)
    // points in each 1/64 of the pixel's width, so the covered count is 0.7 x 64 within 2:
    // tolerance 2/64. One shared position would make the pixel 0 or 1.
    EXPECT_NEAR(img.color[img.index(3, y)].r, 1.0f - (kEdgeX - 3.0f), 2.0f / 64.0f) << y;
    EXPECT_EQ(img.color[img.index(2, y)].r, 0.0f) << y;  // wholly left of the edge
    EXPECT_EQ(img.color[img.index(4, y)].r, 1.0f) << y;  // wholly right of it
  }
}

TEST_P(Antialiasing, FramesOfOneSampleAccumulateAsOneFrameOfMany) {
  // Frame f's only sample has index f; one frame's sample s has index s: the same 16
  // positions, so the same coverage. The sums differ only by float rounding of 16 terms.
  const Renderer r;
  const EyeImage many = r.render(GetParam(), 16, 0);
  std::vector<float> mean(size_t(kSize) * kSize, 0.0f);
  for (uint32_t f = 0; f < 16; ++f) {
    const EyeImage one = r.render(GetParam(), 1, f);
    for (size_t i = 0; i < mean.size(); ++i) mean[i] += one.color[i].r / 16.0f;
  }
  for (size_t i = 0; i < mean.size(); ++i) EXPECT_NEAR(mean[i], many.color[i].r, 1e-6f) << i;
}

INSTANTIATE_TEST_SUITE_P(Samplers, Antialiasing,
                         ::testing::Values(SamplerKind::Random, SamplerKind::Sobol),
                         [](const ::testing::TestParamInfo<SamplerKind>& i) {
                           return std::string(samplerName(i.param));
                         });

}  // namespace
}  // namespace photovr
