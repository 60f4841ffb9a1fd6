#include "trace/embree_scene.h"

#include <gtest/gtest.h>

#include "tests/trace/trace_test_util.h"
#include "trace/surface.h"

namespace photovr {
namespace {

using testing::addSquare;
using testing::diffuseMaterial;

constexpr float kInf = 1e30f;

Scene oneSquare(const glm::mat4& t, bool doubleSided = false) {
  Scene s;
  s.materials.push_back(diffuseMaterial(glm::vec3(0.5f)));
  s.materials[0].doubleSided = doubleSided;
  addSquare(s, 1.0f, 0, t);
  return s;
}

TEST(EmbreeScene, HitDistanceAndBarycentricsOfAKnownSquare) {
  const Scene s = oneSquare(glm::translate(glm::mat4(1.0f), {0, 0, -3}));
  const EmbreeScene e(s);
  const TraceHit h = e.intersect({0.5f, -0.5f, 0}, {0, 0, -1}, 0, kInf);
  ASSERT_TRUE(h.hit);
  EXPECT_FLOAT_EQ(h.t, 3.0f);
  EXPECT_EQ(h.instance, 0u);
  const SurfaceHit sh = surfaceAt(s, h.instance, h.triangle, h.b1, h.b2, {0, 0, -1});
  // Rebuilt from barycentrics: float rounding of coordinates of size ~3.
  EXPECT_NEAR(glm::distance(sh.position, glm::vec3(0.5f, -0.5f, -3.0f)), 0.0f, 1e-6f);
  EXPECT_FALSE(e.intersect({0.5f, -0.5f, 0}, {0, 0, -1}, 0, 2.9f).hit);  // tfar respected
}

TEST(EmbreeScene, CameraRaysCullSingleSidedBackFacesLikeTheGBuffer) {
  const Scene s = oneSquare(glm::translate(glm::mat4(1.0f), {0, 0, -3}));
  const EmbreeScene e(s);
  EXPECT_TRUE(e.stats().cameraBackFaceCulling);
  EXPECT_EQ(e.stats().filteredMeshes, 0u);  // an opaque mesh needs no any-hit filter
  EXPECT_FALSE(e.intersect({0, 0, -6}, {0, 0, 1}, 0, kInf, RayRole::Camera).hit);  // from behind
  EXPECT_TRUE(e.intersect({0, 0, 0}, {0, 0, -1}, 0, kInf, RayRole::Camera).hit);   // in front
  const Scene two = oneSquare(glm::translate(glm::mat4(1.0f), {0, 0, -3}), true);
  const EmbreeScene doubleSided(two);
  EXPECT_FALSE(doubleSided.stats().cameraBackFaceCulling);
  EXPECT_TRUE(doubleSided.intersect({0, 0, -6}, {0, 0, 1}, 0, kInf, RayRole::Camera).hit);
}

TEST(EmbreeScene, TransportRaysMeetSingleSidedSurfacesFromBothSides) {
  // A one-sided wall blocks light from behind as from in front: no light leaks through it.
  const Scene s = oneSquare(glm::translate(glm::mat4(1.0f), {0, 0, -3}));
  const EmbreeScene e(s);
  const TraceHit behind = e.intersect({0, 0, -6}, {0, 0, 1}, 0, kInf);
  ASSERT_TRUE(behind.hit);
  EXPECT_FLOAT_EQ(behind.t, 3.0f);
  EXPECT_TRUE(e.occluded({0, 0, -6}, {0, 0, 1}, 0, kInf));
  BatchRayHit bounce;
  bounce.ray.set({0, 0, -6}, {0, 0, 1}, 0.0f, kInf);
  e.intersectBatch(&bounce, 1, BatchCall::Stream);
  EXPECT_TRUE(bounce.traceHit().hit);
  BatchRayHit primary;
  primary.ray.set({0, 0, -6}, {0, 0, 1}, 0.0f, kInf);
  e.intersectBatch(&primary, 1, BatchCall::Stream, RayRole::Camera);
  EXPECT_FALSE(primary.traceHit().hit);
}

TEST(EmbreeScene, MirroredInstanceKeepsItsFrontFace) {
  // Scale x by -1: winding flips in world space, but the face still faces +Z in its own
  // space, as the G-buffer sees it (GBufferFeatures.MirroredInstance...).
  const glm::mat4 t = glm::scale(glm::translate(glm::mat4(1.0f), {0, 0, -3}), {-1, 1, 1});
  // One mesh, one instance: traced with one level, in world space, where the winding is
  // mirrored; the same mesh shared by three more instances far away (a fourfold copy) keeps
  // two levels.
  Scene s = oneSquare(t);  // EmbreeScene keeps a reference: the scene must outlive it
  const EmbreeScene e(s);
  ASSERT_EQ(e.stats().instancesInTopLevel, 1u);
  EXPECT_TRUE(e.intersect({0.2f, 0.3f, 0}, {0, 0, -1}, 0, kInf, RayRole::Camera).hit);
  EXPECT_FALSE(e.intersect({0.2f, 0.3f, -6}, {0, 0, 1}, 0, kInf, RayRole::Camera).hit);
  Scene shared = s;
  for (const float x : {100.0f, 200.0f, 300.0f})
    shared.instances.push_back(
        {0, glm::translate(glm::mat4(1.0f), {x, 0, 0}), glm::mat4(1.0f), "far"});
  const EmbreeScene e2(shared);
  ASSERT_EQ(e2.stats().instancesInTopLevel, 0u);
  EXPECT_TRUE(e2.intersect({0.2f, 0.3f, 0}, {0, 0, -1}, 0, kInf, RayRole::Camera).hit);
  EXPECT_FALSE(e2.intersect({0.2f, 0.3f, -6}, {0, 0, 1}, 0, kInf, RayRole::Camera).hit);
}

// A mesh shared by a mirrored and an unmirrored instance, copied into one level: each copy
// culls its own back faces (the camera filter's data is per copy, not per mesh).
TEST(EmbreeScene, SharedMeshCopiesKeepTheirOwnFrontFaces) {
  const glm::mat4 plain = glm::translate(glm::mat4(1.0f), {0, 0, -3});
  Scene s = oneSquare(glm::scale(plain, {-1, 1, 1}));  // mirrored
  s.instances.push_back({0, glm::translate(plain, {5, 0, 0}), glm::mat4(1.0f), "plain"});
  const EmbreeScene e(s);
  ASSERT_EQ(e.stats().instancesInTopLevel, 2u);
  for (const float x : {0.2f, 5.2f}) {
    const TraceHit front = e.intersect({x, 0.3f, 0}, {0, 0, -1}, 0, kInf, RayRole::Camera);
    ASSERT_TRUE(front.hit) << x;
    EXPECT_EQ(front.instance, x < 1.0f ? 0u : 1u);
    EXPECT_FALSE(e.intersect({x, 0.3f, -6}, {0, 0, 1}, 0, kInf, RayRole::Camera).hit) << x;
  }
}

TEST(EmbreeScene, AlphaMaskHolesLetRaysThrough) {
  Scene s = oneSquare(glm::translate(glm::mat4(1.0f), {0, 0, -3}));
  Texture t;
  t.name = "half";
  t.width = 2;
  t.height = 1;
  t.nearest = true;
  t.rgba = {255, 255, 255, 255, 255, 255, 255, 0};  // u < 0.5 opaque, u >= 0.5 clear
  s.textures.push_back(t);
  s.materials[0].alphaMode = AlphaMode::Mask;
  s.materials[0].baseColorTexture.texture = 0;
  const EmbreeScene e(s);
  EXPECT_TRUE(e.stats().alphaFilter);
  EXPECT_TRUE(e.intersect({-0.5f, 0, 0}, {0, 0, -1}, 0, kInf).hit);  // u = 0.25
  EXPECT_FALSE(e.intersect({0.5f, 0, 0}, {0, 0, -1}, 0, kInf).hit);  // u = 0.75
  EXPECT_FALSE(e.occluded({0.5f, 0, 0}, {0, 0, -1}, 0, kInf));
  // A camera ray runs both filters: the hole and, single-sided, the back face.
  EXPECT_TRUE(e.intersect({-0.5f, 0, 0}, {0, 0, -1}, 0, kInf, RayRole::Camera).hit);
  EXPECT_FALSE(e.intersect({0.5f, 0, 0}, {0, 0, -1}, 0, kInf, RayRole::Camera).hit);
  EXPECT_FALSE(e.intersect({-0.5f, 0, -6}, {0, 0, 1}, 0, kInf, RayRole::Camera).hit);
  EXPECT_TRUE(e.intersect({-0.5f, 0, -6}, {0, 0, 1}, 0, kInf).hit);
}

// Where copying the shared meshes into world space at most doubles the triangles, every
// instance's mesh goes into the top level (one BVH level) and a hit still names its instance;
// a mesh shared more widely keeps the two levels. The same rays find the same instances and
// triangles either way.
TEST(EmbreeScene, OneLevelWhereCopiesAreCheapAndHitsStillNameTheirInstance) {
  Scene unique = oneSquare(glm::translate(glm::mat4(1.0f), {0, 0, -3}));
  addSquare(unique, 1.0f, 0, glm::translate(glm::mat4(1.0f), {5, 0, -3}));
  Scene cheap = unique;  // a third square from the second's mesh: 3 squares' triangles for 2
  cheap.instances.push_back({1, glm::translate(glm::mat4(1.0f), {50, 0, -3}), glm::mat4(1.0f), ""});
  EXPECT_EQ(EmbreeScene(cheap).stats().instancesInTopLevel, 3u);
  Scene shared = unique;
  shared.meshes.pop_back();
  shared.instances[1].mesh = 0;          // both squares from one mesh ...
  for (const float y : {50.0f, 100.0f})  // ... and two more of it far away: fourfold
    shared.instances.push_back(
        {0, glm::translate(glm::mat4(1.0f), {0, y, -3}), glm::mat4(1.0f), ""});
  const EmbreeScene one(unique), two(shared);
  EXPECT_EQ(one.stats().instancesInTopLevel, 2u);
  EXPECT_EQ(one.stats().meshBvhs, 0u);
  EXPECT_EQ(two.stats().instancesInTopLevel, 0u);
  EXPECT_EQ(two.stats().meshBvhs, 1u);
  for (const float x : {0.25f, 5.25f}) {
    const TraceHit a = one.intersect({x, 0.5f, 0}, {0, 0, -1}, 0, kInf, RayRole::Camera);
    const TraceHit b = two.intersect({x, 0.5f, 0}, {0, 0, -1}, 0, kInf, RayRole::Camera);
    ASSERT_TRUE(a.hit && b.hit);
    EXPECT_EQ(a.instance, x < 1.0f ? 0u : 1u);
    EXPECT_EQ(a.instance, b.instance);
    EXPECT_EQ(a.triangle, b.triangle);
    // World-space vertices against a transformed ray: the same hit to float rounding of
    // coordinates of size ~5 (a few ulp).
    EXPECT_NEAR(a.t, b.t, 1e-5f);
    EXPECT_NEAR(a.b1, b.b1, 1e-5f);
    EXPECT_NEAR(a.b2, b.b2, 1e-5f);
    BatchRayHit batch;
    batch.ray.set({x, 0.5f, 0}, {0, 0, -1}, 0.0f, kInf);
    one.intersectBatch(&batch, 1, BatchCall::Stream);
    EXPECT_EQ(batch.traceHit().instance, a.instance);
  }
}

TEST(EmbreeScene, MovedInstancesAreFoundAfterUpdate) {
  Scene s = oneSquare(glm::translate(glm::mat4(1.0f), {0, 0, -3}));
  EmbreeScene e(s);
  s.instances[0].transform = glm::translate(glm::mat4(1.0f), {10, 0, -3});
  e.updateInstanceTransforms();
  EXPECT_FALSE(e.intersect({0, 0, 0}, {0, 0, -1}, 0, kInf).hit);
  EXPECT_TRUE(e.intersect({10, 0, 0}, {0, 0, -1}, 0, kInf).hit);
}

// A skinned mesh's BVH is built for refits; after its vertices move, the refit one finds
// them where they are now.
TEST(EmbreeScene, SkinnedVerticesAreFoundAfterARefit) {
  Scene s = oneSquare(glm::translate(glm::mat4(1.0f), {0, 0, -3}));
  s.meshes[0].skinning.skin = 0;
  EmbreeScene e(s);
  for (glm::vec3& p : s.meshes[0].positions) p.x += 10.0f;
  e.updateMeshVertices({0});
  e.updateInstanceTransforms();
  EXPECT_FALSE(e.intersect({0, 0, 0}, {0, 0, -1}, 0, kInf).hit);
  EXPECT_TRUE(e.intersect({10, 0, 0}, {0, 0, -1}, 0, kInf).hit);
}

// Rays spawned from the point that a ray from 3 m above 'target' (+z) finds on the one
// square of 's', over the hemisphere down to grazing: how many hit that surface again.
int selfHitsAt(const Scene& s, const glm::vec3& target) {
  const EmbreeScene e(s);
  const glm::vec3 origin = target + glm::vec3(0, 0, 3);
  const glm::vec3 dir = glm::normalize(target - origin);
  const TraceHit h = e.intersect(origin, dir, 0, kInf);
  EXPECT_TRUE(h.hit) << "no hit at " << target.x << ", " << target.y << ", " << target.z;
  if (!h.hit) return -1;
  const SurfaceHit sh = surfaceAt(s, h.instance, h.triangle, h.b1, h.b2, dir);
  int selfHits = 0;
  for (int k = 0; k < 64; ++k) {  // directions over the hemisphere, down to grazing
    const float phi = 0.3f * k, cosT = 0.02f + 0.96f * (k % 8) / 7.0f;
    const float sinT = std::sqrt(1 - cosT * cosT);
    glm::vec3 a = std::abs(sh.geometricNormal.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    const glm::vec3 b1 = glm::normalize(glm::cross(sh.geometricNormal, a));
    const glm::vec3 b2 = glm::cross(sh.geometricNormal, b1);
    const glm::vec3 out =
        sinT * std::cos(phi) * b1 + sinT * std::sin(phi) * b2 + cosT * sh.geometricNormal;
    selfHits += e.intersect(offsetRayOrigin(sh, out), out, 0, kInf).hit;
  }
  return selfHits;
}

TEST(SurfaceOffset, SpawnedRaysDoNotHitTheirOwnSurfaceFarFromTheOrigin) {
  // 1e5 m from the origin the float spacing is ~8 mm: a naive epsilon fails there.
  for (float far : {0.0f, 1e3f, 1e5f}) {
    const glm::mat4 t = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(far, far, -far - 3)),
                                    0.7f, glm::normalize(glm::vec3(1, 1, 0)));
    const Scene s = oneSquare(glm::scale(t, glm::vec3(50.0f)));
    EXPECT_EQ(selfHitsAt(s, glm::vec3(t * glm::vec4(0.1f, 0.2f, 0, 1))), 0)
        << "at distance " << far;
  }
}

// Near the origin on a huge triangle the point's error is its vertices' (~1e3 m x float
// epsilon), far above a few hundred ulps of the point itself: a 2 km square through the
// origin, hit within 0.5 m of it. Here the hit's own error bound (positionError) is what
// lifts the origin off the surface; the integer offset alone (Wachter & Binder 2019) is
// ~256 ulps of the point.
TEST(SurfaceOffset, SpawnedRaysDoNotHitAHugeTriangleNearTheOrigin) {
  const glm::mat4 t = glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(glm::vec3(1, 1, 0)));
  const Scene s = oneSquare(glm::scale(t, glm::vec3(1000.0f)));
  for (float r : {0.04f, 0.1f, 0.2f, 0.5f})
    EXPECT_EQ(selfHitsAt(s, glm::vec3(t * glm::vec4(r, 0.7f * r, 0, 1))), 0) << "at " << r;
}

}  // namespace
}  // namespace photovr
