// Glossy reflections after 8 frames: cornell's tall block (metal, roughness 0.25) reflects
// the red wall and the floor, smooth in the reference. With the specular lobe filtered by
// the first a-trous step only (footprint 16 x GGX alpha, gl/denoiser.h) the block stayed
// speckled while the whole image's relMSE, dominated by other regions, was 87x below the
// raw frame's. Judged here by relMSE over the block's pixels alone, against the footprint
// it had before.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/builtin_scenes.h"
#include "core/error_metrics.h"
#include "gl/denoiser.h"
#include "hybrid/denoise_input.h"
#include "hybrid/hybrid_renderer.h"
#include "tests/gl/gl_test_util.h"
#include "tests/hybrid/reference_image.h"
#include "trace/pixel_estimate.h"

namespace photovr {
namespace {

constexpr int kW = 96, kH = 108;  // as denoise_quality_test.cpp

EyeCamera eyeOf(const Scene& s, uint32_t frame) {
  StereoRig rig;
  rig.head = poseOf(s.cameras.at(0));
  return rig.eye(Eye::Left, kW, kH, samplePosition(SamplerKind::Sobol, frame));
}

// The block is cornell's only metal: its diffuse albedo is the demodulation floor. Interior
// pixels only (4-neighbours metal too): at the silhouette the error is the edge's aliasing.
std::vector<char> metalInterior(const EyeImage& img) {
  auto metal = [&](int x, int y) {
    if (x < 0 || y < 0 || x >= kW || y >= kH) return false;
    const size_t i = img.index(x, y);
    return glm::all(glm::lessThanEqual(img.diffuseAlbedo[i], glm::vec3(kMinDemodulationAlbedo))) &&
           img.specularAlbedo[i].g > 0.3f;
  };
  std::vector<char> mask(img.color.size(), 0);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      mask[img.index(x, y)] =
          metal(x, y) && metal(x - 1, y) && metal(x + 1, y) && metal(x, y - 1) && metal(x, y + 1);
  return mask;
}

double maskedRelMse(const std::vector<glm::vec3>& img, const std::vector<glm::vec3>& ref,
                    const std::vector<char>& mask) {
  double sum = 0.0;
  int n = 0;
  for (size_t i = 0; i < img.size(); ++i)
    if (mask[i]) {
      sum += relMsePixel(img[i], ref[i]);
      ++n;
    }
  return sum / std::max(n, 1);
}

TEST(DenoiseGlossy, TallBlockReflectionsAreFilteredOverTheLobe) {
  const Scene scene = makeBuiltinScene("cornell");
  // 512 spp over 32 jitter positions: its own relMSE on the block (raw / 512 ~ 0.002) stays
  // well under the differences measured below.
  const std::vector<glm::vec3> ref = testing::referenceImage(scene, eyeOf(scene, 0), 32, 16, 77);
  testing::osmesaContext();
  HybridRenderer renderer(scene, kW, kH, TraceSettings{});
  gl::DenoiseParams before;  // the footprint until the block was measured
  before.specularFootprint = 16.0f;
  before.specularMaxStep = 16.0f;
  gl::Denoiser now(kW, kH), old(kW, kH, before);
  EyeImage last;
  for (int f = 0; f < 8; ++f) {
    const EyeCamera cam = eyeOf(scene, uint32_t(f));
    last = renderer.render({cam, cam}, 1, uint32_t(f), nullptr)[0];
    const DenoiseInput in = makeDenoiseInput(last);
    for (gl::Denoiser* dn : {&now, &old})
      dn->run(renderer.gbuffer(), {in.eye, in.eye}, 1, gl::DenoiseMode::Full, f == 0);
  }
  const std::vector<char> mask = metalInterior(last);
  const int pixels = int(std::count(mask.begin(), mask.end(), 1));
  ASSERT_GT(pixels, 1000) << "the block covers 1422 interior pixels";
  const double errNow = maskedRelMse(now.readLinear(0), ref, mask);
  const double errOld = maskedRelMse(old.readLinear(0), ref, mask);
  RecordProperty("block_relmse", std::to_string(errNow));
  RecordProperty("block_relmse_footprint16", std::to_string(errOld));
  // Measured, tracer seeds 0 (this test's), 2, 3, 4, 5: now 0.0077, 0.0071, 0.0072, 0.0076,
  // 0.0073; footprint 16 0.0102, 0.0096, 0.0112, 0.0119, 0.0098 (1.32x-1.57x). The bound
  // sits between the two ranges; the ratio is asked with margin below the lowest seen.
  EXPECT_LT(errNow, 0.0086) << "footprint 16: " << errOld;
  EXPECT_LT(errNow * 1.2, errOld) << "now " << errNow;
}

}  // namespace
}  // namespace photovr
