// The hybrid's primary hits rebuilt in batches (rebuildPrimaryHits: intersections and
// geometry in SIMD lanes) are rebuildPrimaryHit's, pixel by pixel and bit for bit, over a
// G-buffer with real hits, misses, records that name nothing and records whose ray misses
// the named triangle.
#include "hybrid/hit_rebuild.h"

#include <gtest/gtest.h>

#include <random>
#include <span>

#include "core/builtin_scenes.h"
#include "tests/trace/surface_bits.h"
#include "trace/embree_scene.h"

namespace photovr {
namespace {

void expectSameBits(const RebuiltHit& a, const RebuiltHit& b, size_t i) {
  EXPECT_EQ(a.direction, b.direction) << i;
  EXPECT_EQ(a.t, b.t) << i;
  EXPECT_EQ(a.outside, b.outside) << i;
  SCOPED_TRACE(::testing::Message() << "pixel " << i);
  testing::expectSameBits(a.surface, b.surface);
}

// A hit of 'cam''s centre pixel, to fill a buffer with before a rebuild writes it.
RebuiltHit stale(const Scene& scene, const EyeCamera& cam) {
  const EmbreeScene embree(scene);
  const glm::vec3 dir = cam.pixelRay(cam.width / 2, cam.height / 2);
  const TraceHit h = embree.intersect(cam.pose.position, dir, 0.0f, 1e30f, RayRole::Camera);
  const VisibilityRecord rec{h.instance, h.triangle, h.b1, h.b2};
  return h.hit ? rebuildPrimaryHit(scene, rec, cam.pose.position, dir) : RebuiltHit{};
}

// Pixel i's record: Embree's hit of its own ray (what the rasterizer records), the
// background where it sees nothing; every fifth a random triangle its ray misses (clamped,
// flagged); every seventh an instance or triangle that does not exist.
gl::GBufferImage gbufferOf(const Scene& scene, const EyeCamera& cam) {
  const EmbreeScene embree(scene);
  gl::GBufferImage g;
  g.width = cam.width;
  g.height = cam.height;
  std::mt19937 rng(5);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const size_t i = g.index(x, y);
      const TraceHit h =
          embree.intersect(cam.pose.position, cam.pixelRay(x, y), 0.0f, 1e30f, RayRole::Camera);
      glm::uvec4 v(kNoHitInstance, 0, 0, 0);
      if (h.hit)
        v = {h.instance, h.triangle, glm::floatBitsToUint(h.b1), glm::floatBitsToUint(h.b2)};
      if (i % 5 == 0) {
        const uint32_t inst = uint32_t(rng() % scene.instances.size());
        const Mesh& mesh = scene.meshes[size_t(scene.instances[inst].mesh)];
        v = {inst, uint32_t(rng() % mesh.triangleCount()), glm::floatBitsToUint(0.25f),
             glm::floatBitsToUint(0.5f)};
      }
      if (i % 7 == 0) v.x = (i % 2) ? uint32_t(scene.instances.size()) : 0u, v.y = ~0u;
      g.visibility.push_back(v);
    }
  return g;
}

TEST(HitRebuild, BatchesEqualOneByOneBitForBit) {
  for (const std::string& name : builtinSceneNames()) {
    SCOPED_TRACE(name);
    const Scene scene = makeBuiltinScene(name);
    StereoRig rig;
    rig.head = poseOf(scene.cameras.at(0));
    const EyeCamera cam = rig.eye(Eye::Right, 23, 17, glm::vec2(0.21f, -0.37f));
    const gl::GBufferImage g = gbufferOf(scene, cam);
    const CameraRays rays(cam);
    const size_t n = g.visibility.size();
    // Filled with another pixel's hit first: a tile's buffer holds the last tile's, and a
    // pixel with no hit gets its ray alone.
    std::vector<RebuiltHit> batch(n, stale(scene, cam));
    const MaterialTable materials(scene);  // the batch's; the one-by-one rebuild computes them
    // Two ranges, neither a multiple of 8 long, as the tracer's tasks split an image.
    uint64_t outside =
        rebuildPrimaryHits(scene, materials, g, rays, cam.pose.position, 0, 100, batch);
    outside += rebuildPrimaryHits(scene, materials, g, rays, cam.pose.position, 100, n,
                                  std::span(batch).subspan(100));  // pixel i's at i - 100
    uint64_t counted = 0, hits = 0;
    for (size_t i = 0; i < n; ++i) {
      const VisibilityRecord rec = g.record(i);
      const int x = int(i % size_t(g.width)), y = int(i / size_t(g.width));
      RebuiltHit one;  // RebuiltHit{} and its ray where the record names nothing
      one.direction = cam.pixelRay(x, y);
      if (!rec.hit()) {  // the background: its ray alone
        EXPECT_EQ(batch[i].direction, one.direction) << i;
        continue;
      }
      if (isValidRecord(scene, rec)) {
        one = rebuildPrimaryHit(scene, rec, cam.pose.position, one.direction);
        ++hits;
      }
      expectSameBits(batch[i], one, i);
      counted += one.outside;
    }
    EXPECT_EQ(outside, counted);
    // Every kind of pixel ran: hits, clamped hits, and pixels with no hit.
    EXPECT_GT(counted, 0u);
    EXPECT_GT(hits, counted);
    EXPECT_LT(hits, n);
  }
}

}  // namespace
}  // namespace photovr
