// Analytic scenes through the whole tracer (STYLE.md 8): each expectation is computed
// independently of the integrator (closed form or quadrature), each tolerance from the
// Monte Carlo error of the estimate or from float rounding.
#include "trace/path_tracer.h"

#include <tbb/global_control.h>

#include <cmath>

#include <gtest/gtest.h>

#include "core/builtin_scenes.h"
#include "tests/trace/reference_bsdf.h"
#include "tests/trace/trace_test_util.h"
#include "trace/sampling.h"

namespace photovr {
namespace {

using testing::addSquare;
using testing::diffuseMaterial;

// A 200 m floor (y = 0, facing +Y) with the given material.
Scene floorScene(const Material& m) {
  Scene s;
  s.materials.push_back(m);
  addSquare(s, 100.0f, 0, glm::rotate(glm::mat4(1.0f), -float(M_PI / 2), glm::vec3(1, 0, 0)));
  return s;
}

struct Estimate {
  double mean = 0.0, standardError = 0.0;
};

// Mean of the red channel of continuePath over n samples at the floor point p seen from wo,
// drawn by the settings' sampler (Sobol unless a test says otherwise). The standard error
// is that of independent samples; a Sobol estimate errs less, so tolerances built on it
// are conservative there.
Estimate estimate(const Scene& s, const TraceSettings& settings, glm::vec3 p, glm::vec3 wo, int n) {
  const EmbreeScene embree(s);
  const LightSet lights(s);
  const TraceContext ctx{s, embree, lights, settings};
  const TraceHit h = embree.intersect(p + wo, -wo, 0.0f, 2.0f);
  EXPECT_TRUE(h.hit);
  const SurfaceHit hit = surfaceAt(s, h.instance, h.triangle, h.b1, h.b2, -wo);
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double v = continuePath(ctx, hit, wo,
                                  {.pixel = 7, .sample = uint32_t(i), .kind = ctx.settings.sampler})
                         .radiance.r;
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / n, var = std::max(0.0, sum2 / n - mean * mean);
  return {mean, std::sqrt(var / n)};
}

// f(wo, wi) cos(theta_i) on the floor (normal +Y), by the reference BSDF: the thesis's
// formulas in double, independent of evalBsdf (tests/trace/reference_bsdf.h; the float
// renderer agrees with it to a few float ulps, bsdf_reference_test.cpp). The cyclic
// permutation (z, x, y) is a rotation taking +Y to the local +z; the BSDF is isotropic.
double bsdfCos(const test::RefMaterial& m, const glm::dvec3& wo, const glm::dvec3& wi) {
  const auto local = [](const glm::dvec3& w) { return glm::dvec3(w.z, w.x, w.y); };
  return test::refBrdf(m, local(wo), local(wi)).r * std::max(0.0, wi.y);
}

test::RefMaterial materialOf(const Material& m) {
  return {glm::dvec3(m.baseColorFactor), m.metallicFactor, m.roughnessFactor};
}

TEST(PathTracer, PointLightOverAPlaneGivesCosOverRSquaredAtEveryAngle) {
  const Material m = diffuseMaterial(glm::vec3(0.6f));
  Scene s = floorScene(m);
  Light l;
  l.position = {0, 1, 0};
  l.intensity = 5.0f;
  s.lights.push_back(l);
  TraceSettings settings;
  settings.maxBounces = 0;  // one vertex: NEE to the light; BSDF rays escape into black
  const glm::vec3 wo = glm::normalize(glm::vec3(-0.3f, 1.0f, 0.2f));
  for (float x : {0.0f, 1.0f, 5.0f, 30.0f}) {  // light zenith angle 0, 45, 79, 88 degrees
    const glm::vec3 p(x, 0, 0);
    const glm::vec3 toLight = l.position - p;
    const double r2 = glm::dot(toLight, toLight);
    const double expected = bsdfCos(materialOf(m), wo, glm::normalize(toLight)) * l.intensity / r2;
    const Estimate e = estimate(s, settings, p, wo, 8);
    // Deterministic (a delta light, nothing else to hit): float rounding only. The hit is
    // rebuilt from barycentrics of a 200 m triangle, ~200 m x 6e-8 = 1.2e-5 m off, which
    // moves cos/r^2 by up to ~3 x 1.2e-5 / r relative: 1e-4 covers r >= 1 m and the
    // float BSDF's few ulps (< 1e-6) from the double reference.
    EXPECT_NEAR(e.mean, expected, 1e-4 * expected) << "x = " << x;
  }
}

// A square's placement at height y over the origin, facing down (-Y).
glm::mat4 facingDownAt(float y) {
  return glm::rotate(glm::translate(glm::mat4(1.0f), {0, y, 0}), float(M_PI / 2),
                     glm::vec3(1, 0, 0));
}

// A shadow ray runs the whole way from the shaded point to the light's point: a 2 cm black
// square anywhere between them, up to 1 cm from the light, leaves the point unlit, and one
// 1 cm beyond the light does not touch it. The view is grazing enough that the estimate's
// own ray to the floor point passes beside every square.
TEST(PathTracer, AnOccluderAnywhereUpToThePointLightCastsItsShadow) {
  const Material m = diffuseMaterial(glm::vec3(0.6f));
  Light l;
  l.position = {0, 1, 0};
  l.intensity = 5.0f;
  TraceSettings settings;
  settings.maxBounces = 0;  // NEE alone; BSDF rays escape into black
  const glm::vec3 wo = glm::normalize(glm::vec3(-1.0f, 1.0f, 0.3f));
  const double lit = bsdfCos(materialOf(m), wo, glm::dvec3(0, 1, 0)) * l.intensity;  // r = 1
  for (float y : {0.05f, 0.5f, 0.9f, 0.99f, 1.01f}) {
    Scene s = floorScene(m);
    s.materials.push_back(diffuseMaterial(glm::vec3(0.0f)));
    addSquare(s, 0.01f, 1, facingDownAt(y));
    s.lights.push_back(l);
    const Estimate e = estimate(s, settings, glm::vec3(0.0f), wo, 8);
    if (y < 1.0f)
      EXPECT_EQ(e.mean, 0.0) << "square at y = " << y;  // every shadow ray blocked: exactly 0
    else
      EXPECT_NEAR(e.mean, lit, 1e-4 * lit) << "square at y = " << y;  // as in the test above
  }
}

// The same for an area light: a 10 cm emitter facing down at height 1 and a 20 cm black
// square under it, which hides all of it from the floor point (its half-angle 5.9 degrees
// against the emitter's 2.9), at 3 cm and at 60 cm below it: no light at all, neither by
// next-event estimation nor by the BSDF rays that MIS weighs against it.
TEST(PathTracer, AnOccluderAnywhereUnderTheAreaLightCastsItsShadow) {
  const Material m = diffuseMaterial(glm::vec3(0.6f));
  TraceSettings settings;
  settings.maxBounces = 0;
  const glm::vec3 wo = glm::normalize(glm::vec3(-1.0f, 1.0f, 0.3f));
  for (float y : {0.4f, 0.97f, 2.0f}) {  // 2.0: above the light, for the unshadowed estimate
    Scene s = floorScene(m);
    Material emitter = diffuseMaterial(glm::vec3(0.0f));
    emitter.emissiveFactor = glm::vec3(3.0f);
    s.materials.push_back(emitter);
    s.materials.push_back(diffuseMaterial(glm::vec3(0.0f)));
    addSquare(s, 0.05f, 1, facingDownAt(1.0f));
    addSquare(s, 0.1f, 2, facingDownAt(y));
    const Estimate e = estimate(s, settings, glm::vec3(0.0f), wo, 64);
    if (y < 1.0f)
      EXPECT_EQ(e.mean, 0.0) << "square at y = " << y;
    else  // the emitter's ~0.01 sr at 3 x 0.6 / pi: ~6e-3, well away from 0
      EXPECT_GT(e.mean, 1e-3) << "square at y = " << y;
  }
}

TEST(PathTracer, RectangularAreaLightOverAPlaneMatchesQuadrature) {
  const Material m = diffuseMaterial(glm::vec3(0.7f));
  Scene s = floorScene(m);
  Material emitter = diffuseMaterial(glm::vec3(0.0f));
  emitter.emissiveFactor = glm::vec3(3.0f);
  s.materials.push_back(emitter);
  // 1 x 1 m emitter at height 1, facing down, centred above (0.4, 0, 0).
  const glm::mat4 t = glm::rotate(glm::translate(glm::mat4(1.0f), {0.4f, 1.0f, 0.0f}),
                                  float(M_PI / 2), glm::vec3(1, 0, 0));
  addSquare(s, 0.5f, 1, t);
  TraceSettings settings;
  settings.maxBounces = 0;
  const glm::vec3 wo = glm::normalize(glm::vec3(0.5f, 1.0f, 0.0f));
  // Quadrature: midpoint rule on a 400 x 400 grid, dw = cos_light dA / r^2; its error on
  // this smooth integrand is ~1e-5 relative, far below the Monte Carlo tolerance.
  double expected = 0.0;
  const int n = 400;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const glm::vec3 q(0.4f - 0.5f + (i + 0.5f) / n, 1.0f, -0.5f + (j + 0.5f) / n);
      const double r2 = glm::dot(q, q);
      const glm::vec3 wi = q / float(std::sqrt(r2));
      expected += bsdfCos(materialOf(m), wo, wi) * 3.0 * (wi.y / r2) / (n * n);
    }
  const Estimate e = estimate(s, settings, glm::vec3(0.0f), wo, 20000);
  // 4 standard errors: a false failure once in ~16000 runs (normal tails).
  EXPECT_NEAR(e.mean, expected, 4.0 * e.standardError + 1e-6);
  EXPECT_LT(e.standardError, 0.02 * expected);  // MIS keeps the estimate tight
}

TEST(PathTracer, WhiteFurnacePlaneReflectsItsDirectionalAlbedo) {
  Material m = diffuseMaterial(glm::vec3(1.0f));
  Scene s = floorScene(m);
  s.environment.type = Environment::Type::Constant;
  s.environment.constant = glm::vec3(1.0f);
  TraceSettings settings;
  settings.maxBounces = 4;
  for (float angle : {0.0f, 60.0f, 85.0f}) {
    const float a = glm::radians(angle);
    const glm::vec3 wo(std::sin(a), std::cos(a), 0.0f);
    // Directional albedo by quadrature over the hemisphere (512 x 1024 midpoint cells in
    // cos(theta) and phi; error ~1e-4 relative for this rough lobe).
    double albedo = 0.0;
    const int nt = 512, np = 1024;
    for (int i = 0; i < nt; ++i)
      for (int j = 0; j < np; ++j) {
        const double ct = (i + 0.5) / nt, st = std::sqrt(1 - ct * ct),
                     ph = 2 * M_PI * (j + 0.5) / np;
        const glm::dvec3 wi(st * std::cos(ph), ct, st * std::sin(ph));
        albedo += bsdfCos(materialOf(m), wo, wi) * (2 * M_PI / (nt * np));  // dw = dcos dphi
      }
    const Estimate e = estimate(s, settings, glm::vec3(0.0f), wo, 4000);
    EXPECT_NEAR(e.mean, albedo, 4.0 * e.standardError + 2e-4) << angle << " degrees";
    EXPECT_LE(albedo, 1.0 + 1e-3);
  }
}

EyeImage renderSmall(const Scene& scene, int spp) {
  const EmbreeScene embree(scene);
  const LightSet lights(scene);
  TraceSettings settings;
  settings.samplesPerPixel = spp;
  const TraceContext ctx{scene, embree, lights, settings};
  StereoRig rig;
  rig.head = poseOf(scene.cameras.at(0));
  return renderPathTraced(ctx, rig.eye(Eye::Left, 24, 27, samplePosition(SamplerKind::Sobol, 0)), 0,
                          0);
}

TEST(PathTracer, FramesAreBitIdenticalWhateverTheThreadCount) {
  const Scene scene = makeBuiltinScene("cornell");
  EyeImage one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = renderSmall(scene, 2);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = renderSmall(scene, 2);
  }
  EXPECT_EQ(one.color, two.color);
  EXPECT_EQ(one.rays, two.rays);
}

TEST(PathTracer, NoNaNOrInfOnAnyBuiltinScene) {
  for (const std::string& name : builtinSceneNames()) {
    const EyeImage img = renderSmall(makeBuiltinScene(name), 1);
    EXPECT_EQ(img.rejectedSamples, 0u) << name;
    for (const glm::vec3& c : img.color) ASSERT_TRUE(isFinite(c)) << name;
    double sum = 0;
    for (const glm::vec3& c : img.color) sum += c.r + c.g + c.b;
    EXPECT_GT(sum, 0.0) << name << " rendered black";
  }
}

}  // namespace
}  // namespace photovr
