// Each skip of work a scene does not need (trace/work_skips.h) changes nothing but the work:
// the image with the skip turned off agrees within Monte Carlo error, and turning it off
// really does the extra work (more rays, more filtered meshes), so the test can fail.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/builtin_scenes.h"
#include "tests/trace/image_statistics.h"
#include "trace/path_tracer.h"

namespace photovr {
namespace {

struct SkipRun {
  testing::FrameStatistics stats;
  uint64_t standInRays = 0;  // shadow rays towards a dark stand-in (see below)
  size_t filteredMeshes = 0, standIns = 0;
};

// 'frames' independent 2-spp frames of one 24 x 27 eye (a ~1/40 DK2 eye: fast, still every
// part of the scene); the same camera and jitter each frame, so only the noise differs.
SkipRun render(const Scene& scene, const WorkSkips& skips, int frames = 16) {
  TraceSettings settings;
  settings.samplesPerPixel = 2;
  settings.skips = skips;
  EmbreeScene embree(scene, skips);
  const LightSet lights(scene, skips);
  const TraceContext ctx{scene, embree, lights, settings};
  StereoRig rig;
  rig.head = poseOf(scene.cameras.at(0));
  const EyeCamera cam = rig.eye(Eye::Left, 24, 27, glm::vec2(0.0f));
  std::vector<std::vector<glm::vec3>> colors;
  SkipRun run;
  RayRecorder recorder;
  embree.setRecorder(&recorder);
  for (int f = 0; f < frames; ++f)
    colors.push_back(renderPathTraced(ctx, cam, 0, uint32_t(f)).color);
  embree.setRecorder(nullptr);
  // A stand-in's shadow ray ends at the scene centre (punctual, area) or never (the
  // black environment). The scenes below have no real light of that kind.
  const Bounds b = scene.worldBounds();
  const float radius = glm::length(b.extent());
  for (const RecordedRay& r : recorder.take()) {
    if (r.kind != RecordedRay::Kind::Occluded) continue;
    const bool toCentre = std::isfinite(r.tfar) &&
                          glm::length(r.origin + r.dir * r.tfar - b.center()) < 1e-3f * radius;
    run.standInRays += toCentre || !std::isfinite(r.tfar);
  }
  run.stats = testing::statisticsOf(colors, cam.width, cam.height);
  run.filteredMeshes = embree.stats().filteredMeshes;
  run.standIns = lights.standInCount();
  return run;
}

WorkSkips without(const std::string& name) {
  WorkSkips s;
  s.disable(name);
  return s;
}

// Light classes the scene lacks: off, a dark stand-in is sampled with a shadow ray each.
void expectLightSkipHarmless(const std::string& sceneName, const std::string& skip) {
  const Scene scene = makeBuiltinScene(sceneName);
  const SkipRun on = render(scene, {}), off = render(scene, without(skip));
  EXPECT_EQ(on.standIns, 0u);
  EXPECT_EQ(off.standIns, 1u);
  EXPECT_EQ(on.standInRays, 0u);
  EXPECT_GT(off.standInRays, 0u);
  EXPECT_LT(testing::maxRegionZ(on.stats, off.stats, testing::kRegions), testing::kMaxZ);
}

TEST(WorkSkips, NoPunctualLightsNoShadowRaysForThem) {
  expectLightSkipHarmless("cornell", "punctual-lights");  // cornell: one area light only
}

TEST(WorkSkips, NoEmissiveTrianglesNoAreaSampling) {
  // Spheres without its sun and sky would be black; keep a point light instead, far from
  // the scene centre so its shadow rays are told apart from the stand-in's.
  Scene scene = makeBuiltinScene("spheres");
  scene.environment.type = Environment::Type::None;
  Light lamp;
  lamp.type = Light::Type::Point;
  lamp.position = scene.worldBounds().max + glm::vec3(0.0f, 1.0f, 0.0f);
  lamp.intensity = 50.0f;
  scene.lights = {lamp};
  const SkipRun on = render(scene, {}), off = render(scene, without("area-lights"));
  EXPECT_EQ(off.standIns, 1u);
  EXPECT_EQ(on.standInRays, 0u);
  EXPECT_GT(off.standInRays, 0u);
  EXPECT_LT(testing::maxRegionZ(on.stats, off.stats, testing::kRegions), testing::kMaxZ);
}

TEST(WorkSkips, NoEnvironmentNoEnvironmentSampling) {
  expectLightSkipHarmless("cornell", "environment");  // cornell: closed box, no environment
}

TEST(WorkSkips, AnyHitFilterOnlyWhereNeeded) {
  // Cornell made double-sided and opaque everywhere needs no filter. Off, every mesh gets one.
  Scene scene = makeBuiltinScene("cornell");
  for (Material& m : scene.materials) m.doubleSided = true;
  const SkipRun on = render(scene, {}, 8), off = render(scene, without("any-hit"), 8);
  EXPECT_EQ(on.filteredMeshes, 0u);
  EXPECT_EQ(off.filteredMeshes, scene.meshes.size());
  // The filter accepts every hit on an opaque double-sided mesh: the very same image.
  EXPECT_EQ(on.stats.mean, off.stats.mean);
}

// Issue 23: a textured emitter's triangles are sampled by the power the texture gives
// them. The panel's lit square (12.5 cm, 4 x 4 of its 64 x 64 texels) is 2 x 2 of its
// 32 x 32 cells, cell edges on texel edges: exactly 8 of its 2048 triangles emit.
TEST(WorkSkips, DarkEmitterTrianglesAreNotLightSampled) {
  const Scene scene = makeCornellTexturedLight();
  EXPECT_EQ(LightSet(scene).areaTriangleCount(), 8u);
  EXPECT_EQ(LightSet(scene, without("dark-emitters")).areaTriangleCount(), 2048u);
  const SkipRun on = render(scene, {}), off = render(scene, without("dark-emitters"));
  // The same image (both unbiased: a triangle left out is still found by BSDF rays, with MIS
  // weight 1) ...
  EXPECT_LT(testing::maxRegionZ(on.stats, off.stats, testing::kRegions), testing::kMaxZ);
  // ... for less variance: off, 255 of 256 light samples land where the texture is black.
  // Summed over the pixels that do not see the light itself: those at its edge, lit or not
  // by turns under the per-sample pixel positions, have the same huge variance either way.
  double varOn = 0.0, varOff = 0.0;
  for (size_t i = 0; i < on.stats.mean.size(); ++i)
    if (on.stats.mean[i] < 10.0)  // the room is below 1; the light's radiance is ~1e4
      varOn += on.stats.varianceOfMean[i], varOff += off.stats.varianceOfMean[i];
  RecordProperty("variance_off_over_on", std::to_string(varOff / varOn));
  // Measured 24.9x (16 frames of 2 spp, 24 x 27, 8 bounces); the bound asks for a third.
  EXPECT_GT(varOff, 8.0 * varOn);
}

TEST(WorkSkips, PresentLightsAreNeverReplaced) {
  // Cornell has an area light: turning the area-light skip off adds nothing.
  const Scene scene = makeBuiltinScene("cornell");
  EXPECT_EQ(LightSet(scene, without("area-lights")).standInCount(), 0u);
  EXPECT_EQ(LightSet(scene, without("all")).standInCount(), 2u);  // punctual + env
}

TEST(WorkSkips, NamesParse) {
  WorkSkips s;
  s.disable("refit,sky-pixels");
  EXPECT_FALSE(s.refit);
  EXPECT_FALSE(s.skyPixels);
  EXPECT_TRUE(s.environment);
  s.disable("");  // nothing
  EXPECT_TRUE(s.anyHitFilter);
  EXPECT_THROW(s.disable("refit,bogus"), std::invalid_argument);
  for (const std::string& n : WorkSkips::names()) EXPECT_NE(s.flag(n), nullptr) << n;
}

}  // namespace
}  // namespace photovr
