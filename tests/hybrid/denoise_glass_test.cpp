// What is seen through smooth glass, denoised (issue 22): cornell with a clear glass ball
// before the back wall, 8 static 1-spp frames. The tracer moves the denoiser's surface to
// the first vertex beyond a smooth mirror or glass (its lobes, albedo and edge guides:
// docs/ARCHITECTURE.md, "Denoiser"). Judged by relMSE over the ball's interior against a
// converged reference, with the replaced guides and with the glass's own from the G-buffer.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "core/builtin_scenes.h"
#include "core/error_metrics.h"
#include "core/mesh_gen.h"
#include "gl/denoiser.h"
#include "hybrid/denoise_input.h"
#include "hybrid/hybrid_renderer.h"
#include "tests/gl/gl_test_util.h"
#include "tests/hybrid/reference_image.h"

#include <glm/gtc/matrix_transform.hpp>

namespace photovr {
namespace {

constexpr int kW = 96, kH = 108;  // as denoise_quality_test.cpp
const glm::vec3 kCentre(0.3f, 1.0f, -0.4f);
constexpr float kRadius = 0.35f;

Scene glassScene() {
  Scene s = makeBuiltinScene("cornell");
  Material g;
  g.name = "clear-glass";
  g.metallicFactor = 0.0f;
  g.roughnessFactor = 0.0f;
  g.transmissionFactor = 1.0f;
  g.thicknessFactor = 2.0f * kRadius;  // a solid sphere (KHR_materials_volume)
  s.materials.push_back(g);
  Mesh sphere = makeUvSphere(kRadius, 96, 48);
  sphere.name = "glass-ball";
  sphere.material = int(s.materials.size() - 1);
  s.meshes.push_back(sphere);
  Instance inst;
  inst.mesh = int(s.meshes.size() - 1);
  inst.node = "glass-ball";
  inst.transform = inst.previousTransform = glm::translate(glm::mat4(1.0f), kCentre);
  s.instances.push_back(inst);
  return s;
}

EyeCamera eyeOf(const Scene& s, uint32_t frame) {
  StereoRig rig;
  rig.head = poseOf(s.cameras.at(0));
  return rig.eye(Eye::Left, kW, kH, samplePosition(SamplerKind::Sobol, frame));
}

// Pixels whose centre ray meets the sphere at least 1.5 pixels inside its silhouette
// (closed form, independent of the renderer): the silhouette's aliasing is not the
// question here.
std::vector<char> insideSphere(const EyeCamera& cam) {
  std::vector<char> mask(size_t(kW) * kH, 0);
  const glm::vec3 o = cam.pose.position;
  const float pixelAngle = 2.0f * std::atan(cam.fov.up) / float(kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const glm::vec3 d = glm::normalize(cam.rayDirection(x + 0.5f, y + 0.5f));
      const glm::vec3 oc = kCentre - o;
      const float along = glm::dot(oc, d);
      const float miss = std::sqrt(std::max(0.0f, glm::dot(oc, oc) - along * along));
      const float margin = 1.5f * pixelAngle * along;
      mask[size_t(y) * kW + x] = along > 0.0f && miss < kRadius - margin;
    }
  return mask;
}

double maskedRelMse(const std::vector<glm::vec3>& img, const std::vector<glm::vec3>& ref,
                    const std::vector<char>& mask, bool inside) {
  double sum = 0.0;
  int n = 0;
  for (size_t i = 0; i < img.size(); ++i)
    if (bool(mask[i]) == inside) {
      sum += relMsePixel(img[i], ref[i]);
      ++n;
    }
  return sum / std::max(n, 1);
}

struct RegionErrors {
  double inside = 0.0, outside = 0.0;
};

RegionErrors regionErrors(const std::vector<glm::vec3>& img, const std::vector<glm::vec3>& ref,
                          const std::vector<char>& mask) {
  return {maskedRelMse(img, ref, mask, true), maskedRelMse(img, ref, mask, false)};
}

struct GlassRun {
  RegionErrors raw, replaced, glassGuides;
};

// 8 static 1-spp frames under tracer seed 'seed', denoised twice from the same frames: with
// the tracer's replaced guides, and with the G-buffer's (the glass's own) everywhere.
GlassRun runSequence(const Scene& scene, const std::vector<glm::vec3>& ref,
                     const std::vector<char>& mask, uint32_t seed) {
  HybridRenderer renderer(scene, kW, kH, TraceSettings{});
  renderer.setSeed(seed);
  gl::Denoiser replaced(kW, kH), glassGuides(kW, kH);
  GlassRun run;
  for (int f = 0; f < 8; ++f) {
    const EyeCamera cam = eyeOf(scene, uint32_t(f));
    const EyeImage img = renderer.render({cam, cam}, 1, uint32_t(f), nullptr)[0];
    DenoiseInput in = makeDenoiseInput(img);
    replaced.run(renderer.gbuffer(), {in.eye, in.eye}, 1, gl::DenoiseMode::Full, f == 0);
    in.eye.guide = nullptr;
    glassGuides.run(renderer.gbuffer(), {in.eye, in.eye}, 1, gl::DenoiseMode::Full, f == 0);
    if (f == 7) run.raw = regionErrors(img.color, ref, mask);
  }
  run.replaced = regionErrors(replaced.readLinear(0), ref, mask);
  run.glassGuides = regionErrors(glassGuides.readLinear(0), ref, mask);
  return run;
}

TEST(DenoiseGlass, WhatTheGlassShowsIsFilteredAsTheSurfacesItShows) {
  const Scene scene = glassScene();
  // 256 spp over 32 jitter positions: its own error inside the ball (~ raw / 256 ~ 0.001)
  // is small beside the denoised errors compared below.
  const std::vector<glm::vec3> ref = testing::referenceImage(scene, eyeOf(scene, 0), 32, 8, 77);
  const std::vector<char> mask = insideSphere(eyeOf(scene, 0));
  ASSERT_GT(std::count(mask.begin(), mask.end(), 1), 300) << "the ball covers 372 pixels";
  testing::osmesaContext();
  RegionErrors raw, replaced, glassGuides;  // sums over the seeds
  std::string listed;
  for (uint32_t seed = 0; seed < 3; ++seed) {
    const GlassRun r = runSequence(scene, ref, mask, seed);
    raw.inside += r.raw.inside;
    replaced.inside += r.replaced.inside;
    replaced.outside += r.replaced.outside;
    glassGuides.inside += r.glassGuides.inside;
    glassGuides.outside += r.glassGuides.outside;
    listed += " " + std::to_string(r.replaced.inside) + "/" + std::to_string(r.glassGuides.inside);
  }
  RecordProperty("ball_relmse_replaced_over_glass_guides", listed);
  // Measured, tracer seeds 0-2, inside the ball: replaced 0.0278, 0.0237, 0.0282; with the
  // glass's guides 0.0369, 0.0279, 0.0352 (1.18x-1.33x per seed, 1.25x summed); the code
  // before the denoiser surface moved (glass-demodulated specular, seed 0): 0.0349. Raw
  // 0.17-0.28. Outside the ball 0.0234-0.0248 either way (0.3-2 % lower replaced). What is
  // left is mostly bias, the same in every seed: the light's reflection in the ball, a
  // 1-spp firefly that the firefly clamp removes (docs/ARCHITECTURE.md, "Denoiser").
  EXPECT_LT(replaced.inside * 1.12, glassGuides.inside) << listed;
  EXPECT_LT(replaced.outside, glassGuides.outside * 1.01) << "the rest of the frame";
  // Budget: 1.5x the measured sum (0.0797), as denoise_quality_test.cpp's.
  EXPECT_LT(replaced.inside, 1.5 * 0.0797) << listed;
  EXPECT_LT(replaced.inside * 5.0, raw.inside) << "raw " << raw.inside;
}

}  // namespace
}  // namespace photovr
