// Glass (KHR_materials_transmission + _volume), clear coats (KHR_materials_clearcoat) and
// unlit surfaces (KHR_materials_unlit) through the whole tracer: closed forms for a slab, a
// furnace, a coat's Fresnel and an unlit sky, each
// tolerance from the Monte Carlo error of the estimate.
#include <cmath>

#include <gtest/gtest.h>

#include "core/mesh_gen.h"
#include "tests/trace/reference_glass.h"
#include "trace/path_tracer.h"

namespace photovr {
namespace {

Material glassMaterial(bool volume, glm::vec3 attenuation = glm::vec3(1.0f), float distance = 0) {
  Material m;
  m.name = volume ? "glass" : "thin glass";
  m.metallicFactor = 0.0f;
  m.roughnessFactor = 0.0f;
  m.transmissionFactor = 1.0f;
  m.ior = 1.5f;
  m.thicknessFactor = volume ? 1.0f : 0.0f;
  m.attenuationColor = attenuation;
  m.attenuationDistance = distance;
  return m;
}

struct Estimate {
  double mean = 0.0, standardError = 0.0;
};

// The camera's view of the scene along 'dir' from 'eye': the mean red radiance of n paths
// started at the first hit (the first hit's own emission is none here).
Estimate radianceAlong(const Scene& s, glm::vec3 eye, glm::vec3 dir, int n) {
  const EmbreeScene embree(s);
  const LightSet lights(s);
  TraceSettings settings;
  settings.maxBounces = 64;  // light bounces inside glass; Russian roulette ends paths
  const TraceContext ctx{s, embree, lights, settings};
  const TraceHit h = embree.intersect(eye, dir, 0.0f, 1e3f);
  EXPECT_TRUE(h.hit);
  const SurfaceHit hit = surfaceAt(s, h.instance, h.triangle, h.b1, h.b2, dir);
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double v =
        continuePath(ctx, hit, -dir, {.pixel = 3, .sample = uint32_t(i), .kind = settings.sampler})
            .radiance.r;
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

TEST(GlassScene, NonAbsorbingGlassSphereInAWhiteFurnaceIsInvisible) {
  // The white furnace for a dielectric: whatever the paths do inside, with no absorption
  // every path ends in the environment of radiance 1, the 1 / eta^2 of entering undone by
  // leaving. Solid (a volume) and thin-walled; rays through the centre and near the rim
  // (grazing, mostly reflected). Tolerance: 4 standard errors, plus 5e-3 for the energy
  // the smooth lobe's single scattering loses (alpha = 0.045^2) and the facets of a
  // 256 x 128 sphere.
  for (bool volume : {true, false}) {
    Scene s;
    s.materials.push_back(glassMaterial(volume));
    s.meshes.push_back(makeUvSphere(1.0f, 256, 128));
    s.instances.push_back({0, glm::mat4(1.0f), glm::mat4(1.0f), "sphere"});
    s.environment.type = Environment::Type::Constant;
    s.environment.constant = glm::vec3(1.0f);
    for (float offset : {0.0f, 0.6f, 0.95f}) {
      const glm::vec3 eye(offset, 0.013f, 5.0f);
      const Estimate e = radianceAlong(s, eye, glm::vec3(0, 0, -1), 4000);
      EXPECT_NEAR(e.mean, 1.0, 4.0 * e.standardError + 5e-3)
          << (volume ? "solid" : "thin") << " offset " << offset;
    }
  }
}

TEST(GlassScene, SlabTransmittanceIsFresnelAndBeerLambert) {
  // A camera looks through an absorbing glass slab (thickness d, normal incidence) at an
  // emitter of radiance 1 behind it, in a black world. The slab's transmittance with all
  // its internal reflections, Born & Wolf / any optics text:
  //   T = (1 - R)^2 a / (1 - R^2 a^2),  a = exp(-sigma d),  R = ((n - 1) / (n + 1))^2,
  // sigma = -ln(attenuationColor) / attenuationDistance (KHR_materials_volume). The reflected
  // side sees black. Tolerance: 4 standard errors + 1e-3 (R changes by ~1e-6 over the
  // near-normal spread of the smooth lobe).
  const float d = 0.5f, color = 0.5f, distance = 1.0f, n = 1.5f;
  Scene s;
  s.materials.push_back(glassMaterial(true, glm::vec3(color), distance));
  Material emitter;
  emitter.baseColorFactor = glm::vec4(0, 0, 0, 1);
  emitter.emissiveFactor = glm::vec3(1.0f);
  s.materials.push_back(emitter);
  Mesh slab = makeBox({-5, -5, -d}, {5, 5, 0});
  slab.material = 0;
  Mesh light = makeQuad({-20, -20, -2}, {40, 0, 0}, {0, 40, 0});  // faces +z, towards the slab
  light.material = 1;
  s.meshes = {slab, light};
  s.instances = {{0, glm::mat4(1.0f), glm::mat4(1.0f), "slab"},
                 {1, glm::mat4(1.0f), glm::mat4(1.0f), "light"}};
  const double r = std::pow((n - 1.0) / (n + 1.0), 2.0);
  const double a = std::exp(std::log(double(color)) / distance * d);
  const double want = (1 - r) * (1 - r) * a / (1 - r * r * a * a);
  const Estimate e = radianceAlong(s, {0.01f, 0.02f, 3.0f}, glm::vec3(0, 0, -1), 4000);
  RecordProperty("transmittance", std::to_string(e.mean) + " vs " + std::to_string(want));
  EXPECT_NEAR(e.mean, want, 4.0 * e.standardError + 1e-3);
}

// A glass slab (z in [-1.5, 0]) holding a second one (z in [-1, -0.5]), both smooth,
// volumes of these materials, before an emitter of radiance 1 at z = -2 in a black world;
// the camera looks through both at normal incidence.
Scene nestedSlabs(const Material& outer, const Material& inner) {
  Scene s;
  s.materials = {outer, inner};
  Material emitter;
  emitter.baseColorFactor = glm::vec4(0, 0, 0, 1);
  emitter.emissiveFactor = glm::vec3(1.0f);
  s.materials.push_back(emitter);
  Mesh a = makeBox({-5, -5, -1.5f}, {5, 5, 0});
  Mesh b = makeBox({-4, -4, -1.0f}, {4, 4, -0.5f});
  Mesh light = makeQuad({-20, -20, -2}, {40, 0, 0}, {0, 40, 0});
  a.material = 0, b.material = 1, light.material = 2;
  s.meshes = {a, b, light};
  s.instances = {{0, glm::mat4(1.0f), glm::mat4(1.0f), "outer"},
                 {1, glm::mat4(1.0f), glm::mat4(1.0f), "inner"},
                 {2, glm::mat4(1.0f), glm::mat4(1.0f), "light"}};
  return s;
}

TEST(GlassScene, NestedMediaAbsorbAlongEverySegment) {
  // Index-matched (ior 1: no reflection, no bending), absorbing: the light crosses 1.0 of
  // the outer medium (0.5 before the inner slab, 0.5 after) and 0.5 of the inner one, so
  // T = exp(-sigma_o 1.0 - sigma_i 0.5) = 0.5 x 0.25^0.5 = 0.25. A path that does not know
  // it is in the outer medium misses its first 0.5 (0.354). Tolerance: 4 standard errors +
  // 1e-3.
  Material outer = glassMaterial(true, glm::vec3(0.5f), 1.0f);
  Material inner = glassMaterial(true, glm::vec3(0.25f), 1.0f);
  outer.ior = inner.ior = 1.0f;
  const Estimate e =
      radianceAlong(nestedSlabs(outer, inner), {0.01f, 0.02f, 3.0f}, glm::vec3(0, 0, -1), 4000);
  RecordProperty("transmittance", std::to_string(e.mean) + " vs 0.25");
  EXPECT_NEAR(e.mean, 0.25, 4.0 * e.standardError + 1e-3);
}

TEST(GlassScene, AVolumeInsideAnotherRefractsByTheirRatio) {
  // Clear water (ior 1.33) holding a clear slab of the same index: the inner interfaces
  // separate equal media (relative index 1) and must vanish, leaving the water slab's own
  // T = (1 - R) / (1 + R), R = ((n - 1) / (n + 1))^2 (its internal reflections summed).
  // Refracting the inner slab as if it met air would lose ~4 % more (0.923 against 0.961).
  // Tolerance: 4 standard errors + 1e-3.
  Material water = glassMaterial(true), inner = glassMaterial(true);
  water.ior = inner.ior = 1.33f;
  const double r = std::pow((1.33 - 1.0) / (1.33 + 1.0), 2.0), want = (1 - r) / (1 + r);
  const Estimate e =
      radianceAlong(nestedSlabs(water, inner), {0.01f, 0.02f, 3.0f}, glm::vec3(0, 0, -1), 8000);
  RecordProperty("transmittance", std::to_string(e.mean) + " vs " + std::to_string(want));
  EXPECT_NEAR(e.mean, want, 4.0 * e.standardError + 1e-3);
}

TEST(ClearcoatScene, SmoothCoatOverABlackSphereShowsTheCoatsFresnel) {
  // KHR_materials_clearcoat 1 (roughness 0) over a black base with no dielectric specular
  // (KHR_materials_specular 0), in a white furnace: the only light that comes back is the
  // coat's, F(theta) by Schlick with f0 0.04 at the angle the camera ray meets the unit
  // sphere, cos theta = sqrt(1 - offset^2). Tolerance: 4 standard errors + 3e-3 (the
  // facets of a 256 x 128 sphere tilt the normal by ~0.7 degrees; F changes by ~1e-3 per
  // degree at 70 degrees).
  Material coated;
  coated.name = "coated black";
  coated.baseColorFactor = glm::vec4(0, 0, 0, 1);
  coated.metallicFactor = 0.0f;
  coated.specularFactor = 0.0f;
  coated.clearcoatFactor = 1.0f;
  coated.clearcoatRoughnessFactor = 0.0f;
  Scene s;
  s.materials.push_back(coated);
  s.meshes.push_back(makeUvSphere(1.0f, 256, 128));
  s.instances.push_back({0, glm::mat4(1.0f), glm::mat4(1.0f), "sphere"});
  s.environment.type = Environment::Type::Constant;
  s.environment.constant = glm::vec3(1.0f);
  for (float offset : {0.0f, 0.5f, 0.8f, 0.95f}) {
    const glm::vec3 eye(offset, 0.013f, 5.0f);
    const Estimate e = radianceAlong(s, eye, glm::vec3(0, 0, -1), 2000);
    const double c = std::sqrt(1.0 - double(offset) * offset - 0.013 * 0.013);
    const double want = 0.04 + 0.96 * std::pow(1.0 - c, 5.0);
    EXPECT_NEAR(e.mean, want, 4.0 * e.standardError + 3e-3) << "offset " << offset;
  }
}

TEST(UnlitScene, ShowsItsBaseColourToEveryRayAndReflectsNothing) {
  // KHR_materials_unlit: inside an unlit sphere of base colour c (double-sided, seen from
  // within), a white Lambert patch (specular 0) reflects exactly rho c: the sphere's
  // radiance is c towards every ray, found by BSDF sampling alone (it is no light for NEE),
  // and a point light beside it changes nothing of the sphere itself.
  Scene s;
  Material sky;
  sky.unlit = true;
  sky.doubleSided = true;
  sky.baseColorFactor = glm::vec4(0.2f, 0.5f, 0.8f, 1.0f);
  sky.emissiveFactor = glm::vec3(7.0f);  // ignored: unlit shows its base colour
  s.materials.push_back(sky);
  Material patch;
  patch.metallicFactor = 0.0f;
  patch.specularFactor = 0.0f;
  patch.baseColorFactor = glm::vec4(0.6f, 0.6f, 0.6f, 1.0f);
  s.materials.push_back(patch);
  Mesh sphere = makeUvSphere(10.0f, 64, 32);
  s.meshes.push_back(sphere);
  Mesh floor = makeQuad({-0.5f, 0, 0.5f}, {1, 0, 0}, {0, 0, -1});  // faces +y
  floor.material = 1;
  s.meshes.push_back(floor);
  s.instances = {{0, glm::mat4(1.0f), glm::mat4(1.0f), "sky"},
                 {1, glm::mat4(1.0f), glm::mat4(1.0f), "patch"}};
  Light l;
  l.position = {3, 5, 0};
  l.intensity = 50.0f;
  s.lights.push_back(l);
  EXPECT_FALSE(sky.isEmissive());  // not in the light set
  // The sphere seen directly: exactly its base colour (no reflection of the point light).
  const EmbreeScene embree(s);
  const glm::vec3 up = glm::normalize(glm::vec3(0.1f, 1.0f, 0.2f));
  const TraceHit h = embree.intersect({0, 1, 0}, up, 0.0f, 100.0f);
  ASSERT_TRUE(h.hit);
  const SurfaceHit seen = surfaceAt(s, h.instance, h.triangle, h.b1, h.b2, up);
  EXPECT_EQ(seen.emission, glm::vec3(sky.baseColorFactor));
  EXPECT_EQ(evalBsdf(seen.bsdf, {0, 0, 1}, glm::normalize(glm::vec3(1, 0, 1))), glm::vec3(0.0f));
  // The patch without the point light: rho c (4 standard errors + 2e-3 for the sphere's
  // facets).
  s.lights.clear();
  const Estimate e = radianceAlong(s, {0.01f, 1.0f, 0.02f}, glm::vec3(0, -1, 0), 4000);
  EXPECT_NEAR(e.mean, 0.6 * 0.2, 4.0 * e.standardError + 2e-3);
}

}  // namespace
}  // namespace photovr
