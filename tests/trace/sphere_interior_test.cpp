// Thesis-model interreflection with a closed-form structure: inside a sphere of radius R
// with a point light of intensity I at its centre, every surface point sees the same
// radiance field, and a ray leaving point q towards point p makes the same angle with q's
// normal as it makes with p's (the chord is symmetric). So the outgoing radiance L depends
// only on the angle to the normal and solves the 1-D integral equation
//   L(t_o) = f(t_o, 0) I / R^2 + integral over the hemisphere of f(w_o, w_i) L(t_i) cos t_i dw_i,
// solved here by quadrature and iteration, then compared with the full path tracer.
#include <cmath>

#include <gtest/gtest.h>

#include "core/mesh_gen.h"
#include "tests/trace/reference_bsdf.h"
#include "trace/bsdf.h"
#include "trace/path_tracer.h"
#include "trace/sampling.h"

namespace photovr {
namespace {

constexpr int kTheta = 48, kPhi = 96;
const BsdfParams kMaterial{glm::vec3(0.5f), 0.0f, 0.6f};
// The same material for the reference BSDF (tests/trace/reference_bsdf.h): the thesis's
// formulas in double, independent of evalBsdf, so the expectation does not share the
// tracer's BSDF code (the float BSDF agrees with it to a few ulps, bsdf_reference_test.cpp).
const test::RefMaterial kReference{glm::dvec3(kMaterial.baseColor), kMaterial.metallic,
                                   kMaterial.roughness};

glm::vec3 dirAt(double theta, double phi) {
  return {float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
          float(std::cos(theta))};
}

// L at the midpoints of kTheta bins of theta in [0, pi/2), by Neumann iteration.
std::vector<double> solveRadiance(double e0) {
  const double dt = 0.5 * M_PI / kTheta, dp = 2.0 * M_PI / kPhi;
  std::vector<std::vector<double>> k(kTheta, std::vector<double>(kTheta, 0.0));
  std::vector<double> direct(kTheta);
  for (int o = 0; o < kTheta; ++o) {
    const glm::dvec3 wo = test::refDirection((o + 0.5) * dt, 0.0);
    direct[o] = test::refBrdf(kReference, wo, {0, 0, 1}).r * e0;
    for (int i = 0; i < kTheta; ++i)
      for (int p = 0; p < kPhi; ++p) {
        const double ti = (i + 0.5) * dt;
        const glm::dvec3 wi = test::refDirection(ti, (p + 0.5) * dp);
        k[o][i] += test::refBrdf(kReference, wo, wi).r * std::cos(ti) * std::sin(ti) * dt * dp;
      }
  }
  std::vector<double> l = direct;
  for (int it = 0; it < 200; ++it) {  // albedo ~0.5: converges to 1e-60 long before 200
    std::vector<double> next = direct;
    for (int o = 0; o < kTheta; ++o)
      for (int i = 0; i < kTheta; ++i) next[o] += k[o][i] * l[i];
    l = next;
  }
  return l;
}

double interpolate(const std::vector<double>& l, double theta) {
  const double x = theta / (0.5 * M_PI / kTheta) - 0.5;
  const int i = std::clamp(int(std::floor(x)), 0, kTheta - 2);
  const double t = std::clamp(x - i, 0.0, 1.0);
  return l[i] * (1.0 - t) + l[i + 1] * t;
}

TEST(PathTracer, InsideADiffuseSphereWithAPointLightAtItsCentre) {
  const float radius = 2.0f, intensity = 10.0f;
  Scene s;
  Material m;
  m.baseColorFactor = glm::vec4(kMaterial.baseColor, 1.0f);
  m.metallicFactor = kMaterial.metallic;
  m.roughnessFactor = kMaterial.roughness;
  s.materials.push_back(m);
  Mesh sphere = makeUvSphere(radius, 256, 128);
  flipMesh(sphere);  // faces inward: the inside is the front
  s.meshes.push_back(sphere);
  s.instances.push_back({0, glm::mat4(1.0f), glm::mat4(1.0f), "sphere"});
  Light l;
  l.position = glm::vec3(0.0f);
  l.intensity = intensity;
  s.lights.push_back(l);
  const std::vector<double> expected = solveRadiance(intensity / (radius * radius));

  const EmbreeScene embree(s);
  const LightSet lights(s);
  TraceSettings settings;
  settings.maxBounces = 64;  // Russian roulette ends paths long before
  const TraceContext ctx{s, embree, lights, settings};
  const glm::vec3 toWall = glm::normalize(glm::vec3(0.3f, 0.2f, 1.0f));
  const TraceHit h = embree.intersect(glm::vec3(0.0f), toWall, 0.0f, 10.0f);
  ASSERT_TRUE(h.hit);
  const SurfaceHit hit = surfaceAt(s, h.instance, h.triangle, h.b1, h.b2, toWall);
  const Frame frame = Frame::fromZ(hit.shadingNormal);
  for (double thetaDeg : {0.0, 35.0, 70.0}) {
    const double theta = thetaDeg * M_PI / 180.0;
    const glm::vec3 wo = frame.toWorld(dirAt(theta, 1.0));
    double sum = 0.0, sum2 = 0.0;
    const int n = 6000;
    for (int i = 0; i < n; ++i) {
      const double v =
          continuePath(ctx, hit, wo,
                       {.pixel = 11, .sample = uint32_t(i), .kind = ctx.settings.sampler})
              .radiance.r;
      sum += v, sum2 += v * v;
    }
    const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    const double want = interpolate(expected, theta);
    // 4 standard errors (false failure ~6e-5), plus 0.5 % for the quadrature (48 x 96
    // midpoint cells of a smooth integrand) and the facets of a 256 x 128 sphere.
    RecordProperty(
        "deg" + std::to_string(int(thetaDeg)),
        std::to_string(mean) + " vs " + std::to_string(want) + " se " + std::to_string(se));
    EXPECT_NEAR(mean, want, 4.0 * se + 5e-3 * want) << thetaDeg << " degrees";
  }
}

}  // namespace
}  // namespace photovr
