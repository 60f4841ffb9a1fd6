// The geometry stage (trace/hit_geometry.h): the batch's SIMD lanes give the scalar
// function's bits, and the scalar function gives the glm code surfaceAt used before it, so
// that no image changed when the stage came in. The same for named hits (the hybrid's
// primary hits) against the glm code rebuildPrimaryHit used before them.
#include "trace/hit_geometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/builtin_scenes.h"

namespace photovr {
namespace {

glm::vec3 safeNormalize(const glm::vec3& v, const glm::vec3& fallback) {
  const float len = glm::length(v);
  return len > 0.0f && std::isfinite(len) ? v / len : fallback;
}

// surfaceAt's interpolated shading normal as it was written with glm (commit e8471fc), the
// reference: the vertex normals interpolated, times the transform's cofactor matrix.
glm::vec3 glmInterpolatedNormal(const Mesh& mesh, const uint32_t* idx, const glm::mat4& m,
                                const HitRef& hit, const glm::vec3& ng) {
  glm::vec3 n(0.0f);
  if (!mesh.normals.empty()) {
    const float b0 = 1.0f - hit.b1 - hit.b2;
    n = b0 * mesh.normals[idx[0]] + hit.b1 * mesh.normals[idx[1]] + hit.b2 * mesh.normals[idx[2]];
  }
  const glm::vec3 a0(m[0]), a1(m[1]), a2(m[2]);
  glm::vec3 c0 = glm::cross(a1, a2), c1 = glm::cross(a2, a0), c2 = glm::cross(a0, a1);
  if (glm::dot(a0, c0) < 0.0f) c0 = -c0, c1 = -c1, c2 = -c2;
  return safeNormalize(c0 * n.x + c1 * n.y + c2 * n.z, ng);
}

// surfaceAt's geometry as it was written with glm (commit 88ad6c7), the reference.
HitGeometry glmGeometry(const Scene& scene, const HitRef& hit) {
  const Instance& inst = scene.instances[hit.instance];
  const Mesh& mesh = scene.meshes[size_t(inst.mesh)];
  const uint32_t* idx = &mesh.indices[3 * size_t(hit.triangle)];
  const glm::mat4& m = inst.transform;
  const glm::vec3 p0 = glm::vec3(m * glm::vec4(mesh.positions[idx[0]], 1.0f));
  const glm::vec3 p1 = glm::vec3(m * glm::vec4(mesh.positions[idx[1]], 1.0f));
  const glm::vec3 p2 = glm::vec3(m * glm::vec4(mesh.positions[idx[2]], 1.0f));
  HitGeometry g;
  g.position = p0 + hit.b1 * (p1 - p0) + hit.b2 * (p2 - p0);
  const glm::vec3 mag = glm::abs(p0) + glm::abs(hit.b1 * (p1 - p0)) + glm::abs(hit.b2 * (p2 - p0));
  g.positionError = 8.0f * 1.1920929e-7f * std::max(mag.x, std::max(mag.y, mag.z));
  const glm::vec3 n = glm::cross(p1 - p0, p2 - p0);
  const float len = glm::length(n);
  g.ng = len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0, 1, 0);
  g.normal = glmInterpolatedNormal(mesh, idx, m, hit, g.ng);
  return g;
}

// Every float compared as bits: the stage may not change a single rounding.
void expectSameBits(const HitGeometry& a, const HitGeometry& b, size_t i) {
  EXPECT_EQ(a.position, b.position) << i;
  EXPECT_EQ(a.positionError, b.positionError) << i;
  EXPECT_EQ(a.ng, b.ng) << i;
  EXPECT_EQ(a.normal, b.normal) << i;
}

// The same for all but the vertex normal: hitGeometry from a world triangle has none.
void expectSameShape(const HitGeometry& a, const HitGeometry& b, size_t i) {
  EXPECT_EQ(a.position, b.position) << i;
  EXPECT_EQ(a.positionError, b.positionError) << i;
  EXPECT_EQ(a.ng, b.ng) << i;
}

// Random hits over every instance and triangle of a scene; 1001 is no multiple of 8, so a
// partly filled last group of lanes runs too.
std::vector<HitRef> randomHits(const Scene& scene, size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<HitRef> hits;
  while (hits.size() < count) {
    const uint32_t instance = uint32_t(rng() % scene.instances.size());
    const Mesh& mesh = scene.meshes[size_t(scene.instances[instance].mesh)];
    if (mesh.triangleCount() == 0) continue;
    const float b1 = u(rng), b2 = u(rng) * (1.0f - b1);
    hits.push_back({instance, uint32_t(rng() % mesh.triangleCount()), b1, b2});
  }
  return hits;
}

TEST(HitGeometry, BatchEqualsOneByOneAndTheGlmFormBitForBit) {
  for (const std::string& name : builtinSceneNames()) {
    const Scene scene = makeBuiltinScene(name);
    const std::vector<HitRef> hits = randomHits(scene, 1001, 7);
    std::vector<HitGeometry> batch(hits.size());
    hitGeometries(scene, hits, batch);
    for (size_t i = 0; i < hits.size(); ++i) {
      const HitGeometry one = hitGeometry(scene, hits[i]);
      SCOPED_TRACE(name);
      expectSameBits(batch[i], one, i);
      expectSameBits(one, glmGeometry(scene, hits[i]), i);
      const HitRef& h = hits[i];
      const HitGeometry fromCorners =
          hitGeometry(worldTriangle(scene, h.instance, h.triangle), h.b1, h.b2);
      expectSameShape(fromCorners, one, i);
      EXPECT_EQ(fromCorners.normal, fromCorners.ng) << i;
    }
  }
}

// Far from the origin, scaled and sheared, mirrored, and a degenerate triangle (its normal
// is +Y); a mesh with vertex normals, one of them zero and two opposite (at b1 = 0.5,
// b2 = 0.25 the second triangle's cancel out: ng), and the same without normals (ng).
TEST(HitGeometry, FarScaledAndDegenerateTrianglesAgreeToo) {
  Scene scene;
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0.3f, 0}, {0.2f, 1, 0.7f}, {2, 2, 2}, {4, 4, 4}};
  mesh.indices = {0, 1, 2, 3, 4, 3, 0, 3, 4};  // the last two are degenerate (collinear)
  scene.meshes.push_back(mesh);
  mesh.normals = {{0, 0, 1}, {0.6f, 0, 0.8f}, {0, 0, 0}, {0, 1, 0}, {0, -1, 0}};
  scene.meshes.push_back(mesh);
  const glm::mat4 far = glm::mat4(glm::vec4(3e3f, 1.0f, 0, 0), glm::vec4(0, 2e-3f, 0.5f, 0),
                                  glm::vec4(0.1f, 0, 7.0f, 0), glm::vec4(1e7f, -3e6f, 2e5f, 1));
  const glm::mat4 mirror = glm::scale(glm::mat4(1.0f), glm::vec3(-2.0f, 1.0f, 0.5f));
  for (int m = 0; m < 2; ++m) {
    scene.instances.push_back({m, glm::mat4(1.0f), glm::mat4(1.0f), "near"});
    scene.instances.push_back({m, far, far, "far"});
    scene.instances.push_back({m, mirror, mirror, "mirrored"});
  }
  std::vector<HitRef> hits;
  for (uint32_t instance = 0; instance < 6; ++instance)
    for (uint32_t triangle = 0; triangle < 3; ++triangle) {
      for (float b : {0.0f, 0.1f, 0.45f, 0.5f}) hits.push_back({instance, triangle, b, 0.5f * b});
    }
  std::vector<HitGeometry> batch(hits.size());
  hitGeometries(scene, hits, batch);
  for (size_t i = 0; i < hits.size(); ++i) {
    expectSameBits(batch[i], hitGeometry(scene, hits[i]), i);
    expectSameBits(batch[i], glmGeometry(scene, hits[i]), i);
    if (hits[i].triangle > 0) {
      EXPECT_EQ(batch[i].ng, glm::vec3(0, 1, 0)) << i;
    }
  }
}

TEST(HitGeometry, AnEmptyBatchIsNothing) {
  const Scene scene = makeBuiltinScene("cornell");
  std::vector<HitGeometry> none;
  hitGeometries(scene, {}, none);
  EXPECT_TRUE(none.empty());
  std::vector<NamedHit> noHits;
  namedHits(scene, glm::vec3(0.0f), {}, noHits);
  EXPECT_TRUE(noHits.empty());
}

// rebuildPrimaryHit as it was written with glm (commit 8d098a3), the reference: Moller-
// Trumbore with the triangle's world corners, the rasterizer's barycentrics where the ray
// runs parallel to it, barycentrics outside it clamped into it.
NamedHit glmNamedHit(const Scene& scene, const glm::vec3& origin, const NamedRay& ray) {
  const WorldTriangle tri = worldTriangle(scene, ray.hit.instance, ray.hit.triangle);
  const glm::vec3& dir = ray.direction;
  NamedHit r;
  r.hit = ray.hit;
  float& b1 = r.hit.b1;
  float& b2 = r.hit.b2;
  const glm::vec3 e1 = tri.p1 - tri.p0, e2 = tri.p2 - tri.p0;
  const glm::vec3 pv = glm::cross(dir, e2);
  const float det = glm::dot(e1, pv);
  if (det != 0.0f) {
    const float inv = 1.0f / det;
    const glm::vec3 tv = origin - tri.p0;
    const glm::vec3 qv = glm::cross(tv, e1);
    b1 = glm::dot(tv, pv) * inv;
    b2 = glm::dot(dir, qv) * inv;
  } else {
    r.outside = true;
  }
  if (b1 < 0.0f || b2 < 0.0f || b1 + b2 > 1.0f) {
    r.outside = true;
    b1 = std::max(b1, 0.0f);
    b2 = std::max(b2, 0.0f);
    const float sum = b1 + b2;
    if (sum > 1.0f) b1 /= sum, b2 /= sum;
  }
  r.geometry = glmGeometry(scene, r.hit);
  r.t = glm::dot(r.geometry.position - origin, dir);
  return r;
}

void expectSameBits(const NamedHit& a, const NamedHit& b, size_t i) {
  EXPECT_EQ(a.hit.b1, b.hit.b1) << i;
  EXPECT_EQ(a.hit.b2, b.hit.b2) << i;
  EXPECT_EQ(a.t, b.t) << i;
  EXPECT_EQ(a.outside, b.outside) << i;
  expectSameBits(a.geometry, b.geometry, i);
}

// Rays from 'origin' towards random points of random triangles, bent by up to 'bend' so that
// some miss their triangle and are clamped.
std::vector<NamedRay> raysTowards(const Scene& scene, const glm::vec3& origin, float bend,
                                  size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<NamedRay> rays;
  for (const HitRef& h : randomHits(scene, count, seed)) {
    const glm::vec3 to = glmGeometry(scene, h).position - origin;
    const glm::vec3 bent = glm::normalize(to) + bend * glm::vec3(u(rng), u(rng), u(rng));
    rays.push_back({h, glm::normalize(bent)});
  }
  return rays;
}

TEST(HitGeometry, NamedHitsInLanesEqualOneByOneAndTheGlmFormBitForBit) {
  for (const std::string& name : builtinSceneNames()) {
    SCOPED_TRACE(name);
    const Scene scene = makeBuiltinScene(name);
    const glm::vec3 origin(0.31f, 1.57f, 3.9f);
    const std::vector<NamedRay> rays = raysTowards(scene, origin, 0.02f, 1001, 11);
    std::vector<NamedHit> batch(rays.size());
    namedHits(scene, origin, rays, batch);
    size_t outside = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      const NamedHit one = namedHit(scene, origin, rays[i]);
      expectSameBits(batch[i], one, i);
      expectSameBits(one, glmNamedHit(scene, origin, rays[i]), i);
      EXPECT_EQ(one.hit.instance, rays[i].hit.instance);
      EXPECT_EQ(one.hit.triangle, rays[i].hit.triangle);
      outside += one.outside;
    }
    // Both branches ran: bent rays that missed (clamped) and rays that hit.
    EXPECT_GT(outside, 0u);
    EXPECT_LT(outside, rays.size());
  }
}

// A ray in the triangle's plane keeps the rasterizer's barycentrics, flagged; one that hits
// from far away, through a scaled instance, reports the distance and its own barycentrics.
TEST(HitGeometry, ANamedHitParallelOrFarAgreesWithTheGlmForm) {
  Scene scene;
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.indices = {0, 1, 2};
  scene.meshes.push_back(mesh);
  const glm::mat4 far = glm::mat4(glm::vec4(3e3f, 0, 0, 0), glm::vec4(0, 2e-3f, 0, 0),
                                  glm::vec4(0, 0, 7.0f, 0), glm::vec4(1e7f, -3e6f, 2e5f, 1));
  scene.instances.push_back({0, glm::mat4(1.0f), glm::mat4(1.0f), "near"});
  scene.instances.push_back({0, far, far, "far"});
  const std::vector<NamedRay> rays = {
      {{0, 0, 0.2f, 0.3f}, {1, 0, 0}},                                    // in the plane z = 0
      {{0, 0, 0.2f, 0.3f}, glm::normalize(glm::vec3(0.25f, 0.25f, -1))},  // hits at b = 1/4
      {{1, 0, 0.2f, 0.3f}, glm::normalize(glm::vec3(1e7f + 600, -3e6f, 2e5f) - glm::vec3(0))}};
  const glm::vec3 origin(0, 0, 1);
  std::vector<NamedHit> batch(rays.size());
  namedHits(scene, origin, rays, batch);
  for (size_t i = 0; i < rays.size(); ++i) {
    expectSameBits(batch[i], glmNamedHit(scene, origin, rays[i]), i);
    expectSameBits(batch[i], namedHit(scene, origin, rays[i]), i);
  }
  EXPECT_TRUE(batch[0].outside);
  EXPECT_EQ(batch[0].hit.b1, 0.2f);
  EXPECT_EQ(batch[0].hit.b2, 0.3f);
  EXPECT_FALSE(batch[1].outside);
  EXPECT_NEAR(batch[1].hit.b1, 0.25f, 1e-6f);  // float rounding of a unit-scale intersection
  EXPECT_NEAR(batch[1].t, std::sqrt(1.125f), 1e-6f);
}

}  // namespace
}  // namespace photovr
