// alpha BLEND as stochastic coverage (issue 22): a ray meets a BLEND surface with
// probability alpha, independently per layer, in intersection and occlusion queries and
// through the whole tracer. Tolerances: 4 binomial or Monte Carlo standard errors.
#include <cmath>

#include <gtest/gtest.h>

#include "core/camera.h"
#include "core/mesh_gen.h"
#include "trace/embree_scene.h"
#include "trace/path_tracer.h"
#include "trace/rng.h"

namespace photovr {
namespace {

// A square at depth z facing +z, of a black BLEND material with this alpha and emission.
void addLayer(Scene& s, float z, float alpha, float emission, float halfSize = 5.0f) {
  Material m;
  m.baseColorFactor = glm::vec4(0.0f, 0.0f, 0.0f, alpha);
  m.metallicFactor = 0.0f;
  m.alphaMode = alpha < 1.0f ? AlphaMode::Blend : AlphaMode::Opaque;
  m.emissiveFactor = glm::vec3(emission);
  m.specularFactor = 0.0f;
  s.materials.push_back(m);
  Mesh q = makeQuad({-halfSize, -halfSize, z}, {2 * halfSize, 0, 0}, {0, 2 * halfSize, 0});
  q.material = int(s.materials.size() - 1);
  s.meshes.push_back(q);
  s.instances.push_back({int(s.meshes.size() - 1), glm::mat4(1.0f), glm::mat4(1.0f), "layer"});
}

// Rays from random points of a 1 cm square at z = 1, straight down -z.
glm::vec3 origin(Sampler& s) {
  return {0.01f * s.next(), 0.01f * s.next(), 1.0f};
}

TEST(AlphaBlend, EachLayerIsMetWithItsAlphaIndependently) {
  // Two layers, alpha 0.3 above 0.5: the first hit is the top with 0.3, the lower one with
  // 0.7 x 0.5 = 0.35, nothing with 0.35; a shadow ray through both passes with 0.35.
  Scene s;
  addLayer(s, 0.0f, 0.3f, 0.0f);
  addLayer(s, -0.5f, 0.5f, 0.0f);
  const EmbreeScene embree(s);
  Sampler rng = Sampler::make({.pixel = 1, .seed = 5u});
  constexpr int kRays = 40000;
  int top = 0, lower = 0, passed = 0;
  for (int i = 0; i < kRays; ++i) {
    const glm::vec3 o = origin(rng);
    const TraceHit h = embree.intersect(o, {0, 0, -1}, 0.0f, 10.0f);
    top += h.hit && h.instance == 0;
    lower += h.hit && h.instance == 1;
    passed += !embree.occluded(origin(rng), {0, 0, -1}, 0.0f, 10.0f);
  }
  auto expectFraction = [](int count, double p, const char* what) {
    const double sigma = std::sqrt(p * (1 - p) / kRays);
    EXPECT_NEAR(double(count) / kRays, p, 4 * sigma) << what;
  };
  expectFraction(top, 0.3, "top layer");
  expectFraction(lower, 0.35, "lower layer");
  expectFraction(passed, 0.35, "shadow rays through both");
}

// Mean red radiance, and its standard error, of 'frames' path-traced frames of 8 x 8 pixels
// x 16 spp, from 'from' looking at 'at' with a 20 degree field of view.
struct ImageMean {
  double mean = 0.0, se = 0.0;
};
ImageMean meanRadiance(const Scene& s, int maxBounces, glm::vec3 from, glm::vec3 at,
                       uint32_t frames) {
  const EmbreeScene embree(s);
  const LightSet lights(s);
  TraceSettings settings;
  settings.samplesPerPixel = 16;
  settings.maxBounces = maxBounces;
  const TraceContext ctx{s, embree, lights, settings};
  double sum = 0.0, sum2 = 0.0;
  int n = 0;
  for (uint32_t f = 0; f < frames; ++f) {
    EyeCamera cam;
    cam.pose = lookAt(from, at);
    cam.fov = FovTangents::symmetric(glm::radians(20.0f), 1.0f);
    cam.width = cam.height = 8;
    cam.jitter = samplePosition(SamplerKind::Sobol, f);
    for (const glm::vec3& c : renderPathTraced(ctx, cam, 0, f).color) {
      sum += c.r;
      sum2 += double(c.r) * c.r;
      ++n;
    }
  }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

TEST(AlphaBlend, PathTracedImageIsTheAlphaWeightedMix) {
  // A BLEND layer of alpha 0.3 emitting 2 before an opaque wall emitting 1, both black:
  // every pixel's expected radiance is 0.3 x 2 + 0.7 x 1 = 1.3 (the mix alpha blending
  // draws). 8 x 8 pixels x 16 frames x 16 spp.
  Scene s;
  addLayer(s, 0.0f, 0.3f, 2.0f);
  addLayer(s, -1.0f, 1.0f, 1.0f, 50.0f);
  const ImageMean m = meanRadiance(s, 0, {0, 0, 3}, {0, 0, 0}, 16);
  const double mean = m.mean, se = m.se;
  RecordProperty("mean", std::to_string(mean) + " se " + std::to_string(se));
  EXPECT_NEAR(mean, 1.3, 4 * se + 1e-4);
  EXPECT_GT(se, 0.0);  // the coverage is random, not a fixed pattern of all or nothing
}

// A white Lambert floor at z = 0 under a black, double-sided emitter at z = 1 of this
// alpha mode and alpha; the mean radiance of the floor seen from z = 0.5, looking down.
ImageMean floorUnderEmitter(AlphaMode mode, float alpha, float emission, uint32_t frames = 8) {
  Scene s;
  Material floor;
  floor.baseColorFactor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
  floor.metallicFactor = 0.0f;
  floor.specularFactor = 0.0f;
  s.materials.push_back(floor);
  Material light;
  light.baseColorFactor = glm::vec4(0.0f, 0.0f, 0.0f, alpha);
  light.metallicFactor = 0.0f;
  light.specularFactor = 0.0f;
  light.alphaMode = mode;
  light.doubleSided = true;
  light.emissiveFactor = glm::vec3(emission);
  s.materials.push_back(light);
  for (int m = 0; m < 2; ++m) {
    const float z = float(m), half = m == 0 ? 20.0f : 1.0f;
    Mesh q = makeQuad({-half, -half, z}, {2 * half, 0, 0}, {0, 2 * half, 0});
    q.material = m;
    s.meshes.push_back(q);
    s.instances.push_back({m, glm::mat4(1.0f), glm::mat4(1.0f), m == 0 ? "floor" : "light"});
  }
  return meanRadiance(s, 2, {0, 0, 0.5f}, {0, 0, 0}, frames);
}

TEST(AlphaBlend, LightSamplingSeesABlendEmitterAsOftenAsBsdfRaysDo) {
  // BSDF rays meet the emitter with probability alpha = 0.4 (and reflect nothing from it,
  // black, no specular): in expectation the floor is lit as by an opaque emitter of 0.4 x
  // the emission. NEE must count the emitter that much too; counted whole, the floor came
  // out twice as bright here (1.79 against 0.88: NEE + MIS weighed the full emission
  // against 0.4 of it).
  const ImageMean blend = floorUnderEmitter(AlphaMode::Blend, 0.4f, 5.0f);
  const ImageMean opaque = floorUnderEmitter(AlphaMode::Opaque, 1.0f, 2.0f);
  RecordProperty("blend", std::to_string(blend.mean) + " se " + std::to_string(blend.se));
  RecordProperty("opaque", std::to_string(opaque.mean) + " se " + std::to_string(opaque.se));
  // Independent estimates of one mean: 4 combined standard errors.
  EXPECT_NEAR(blend.mean, opaque.mean, 4 * std::hypot(blend.se, opaque.se));
  EXPECT_GT(opaque.mean, 0.1);  // the floor is lit at all
}

TEST(AlphaBlend, AMaskEmitterThatIsAllHoleLightsNothing) {
  // alpha 0.3 under MASK's cutoff 0.5: the emitter is a hole everywhere, no ray meets it,
  // and light sampling may not find light there either.
  const ImageMean mask = floorUnderEmitter(AlphaMode::Mask, 0.3f, 5.0f, 2);
  EXPECT_EQ(mask.mean, 0.0);
}

}  // namespace
}  // namespace photovr
