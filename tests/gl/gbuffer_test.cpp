#include "gl/gbuffer.h"

#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "core/visibility.h"
#include "gl/draw_stats.h"
#include "gl/gbuffer_readback.h"
#include "tests/gl/gl_test_util.h"

namespace photovr {
namespace {

using testing::osmesaContext;
using testing::plainMaterial;
using testing::rectangleMesh;

constexpr float kEps = std::numeric_limits<float>::epsilon();
// Half floats keep 11 significant bits: relative rounding error <= 2^-11.
constexpr float kHalfRel = 1.0f / 2048.0f;

struct Rendered {
  gl::GBufferImage eye[2];
  gl::DrawStats stats;
};

Rendered renderGBuffer(const Scene& scene, const std::array<EyeCamera, 2>& eyes,
                       gl::EyeRouting routing = gl::EyeRouting::Layered) {
  osmesaContext();  // makes it current
  gl::SceneGpu gpu(scene);
  gl::GBufferPass pass(eyes[0].width, eyes[0].height, routing);
  gl::resetDrawStats();
  const std::array<glm::mat4, 2> previous = {eyes[0].unjitteredProjection() * eyes[0].view(),
                                             eyes[1].unjitteredProjection() * eyes[1].view()};
  pass.render(gpu, eyes, previous);
  Rendered r;
  r.stats = gl::drawStats();
  r.eye[0] = pass.read(0);
  r.eye[1] = pass.read(1);
  return r;
}

// A wall facing the viewer at z = -distance, 200 m wide so it fills every view.
Scene wallScene(float distance, glm::vec3 color = glm::vec3(0.2f, 0.5f, 0.8f)) {
  Scene s;
  s.materials.push_back(plainMaterial(color, 0.25f, 0.75f));
  s.meshes.push_back(rectangleMesh(100.0f, 100.0f, 0));
  Instance inst;
  inst.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -distance));
  inst.previousTransform = inst.transform;
  s.instances.push_back(inst);
  return s;
}

std::array<EyeCamera, 2> stereoEyes(int w, int h, glm::vec2 jitter = glm::vec2(0.0f)) {
  StereoRig rig;  // head at the origin looking down -Z, DK2 FOV, 63.5 mm IPD
  return {rig.eye(Eye::Left, w, h, jitter), rig.eye(Eye::Right, w, h, jitter)};
}

TEST(GBuffer, WallAtKnownDistanceGivesAnalyticReversedZDepth) {
  const float distance = 3.0f;
  const auto eyes = stereoEyes(48, 40, {0.25f, -0.125f});
  const Rendered r = renderGBuffer(wallScene(distance), eyes);
  for (int e = 0; e < 2; ++e) {
    const float expected = eyes[e].znear / distance;  // depth = near / view distance
    for (float d : r.eye[e].depth)
      // GL interpolates z/w per fragment in float: a few ulp of the value.
      ASSERT_NEAR(d, expected, 4.0f * kEps * expected);
  }
}

TEST(GBuffer, VisibilityRecordRebuildsTheAnalyticHitPoint) {
  // Barycentrics in float carry ~eps relative error, i.e. eps x triangle size in position:
  // a 12 m wall seen from 2 m keeps that near 1e-6 relative. (A 200 m triangle would not:
  // 6e-8 x 280 m = 1.7e-5 m. The tracer re-intersects the triangle for that reason.)
  Scene scene = wallScene(2.0f);
  scene.meshes[0] = rectangleMesh(6.0f, 6.0f, 0);
  // Tilt the wall so depth varies across the image and barycentrics are non-trivial.
  scene.instances[0].transform =
      glm::rotate(scene.instances[0].transform, 0.6f, glm::normalize(glm::vec3(1, 2, 0)));
  const auto eyes = stereoEyes(40, 32, {-0.3f, 0.2f});
  const Rendered r = renderGBuffer(scene, eyes);
  const glm::vec3 n = glm::mat3(scene.instances[0].transform) * glm::vec3(0, 0, 1);
  const glm::vec3 p = glm::vec3(scene.instances[0].transform[3]);
  int checked = 0;
  for (int e = 0; e < 2; ++e)
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 40; ++x) {
        const glm::uvec4 v = r.eye[e].visibility[r.eye[e].index(x, y)];
        if (v.x == kNoHitInstance) continue;
        const VisibilityRecord rec{v.x, v.y, glm::uintBitsToFloat(v.z), glm::uintBitsToFloat(v.w)};
        ASSERT_TRUE(isValidRecord(scene, rec));
        // Analytic: the ray of this pixel's jittered sample hits the plane dot(n, x - p) = 0.
        const glm::dvec3 o(eyes[e].pose.position), d(eyes[e].pixelRay(x, y));
        const double t = glm::dot(glm::dvec3(n), glm::dvec3(p) - o) / glm::dot(glm::dvec3(n), d);
        const glm::dvec3 analytic = o + t * d;
        const glm::vec3 rebuilt = rebuildHitPoint(scene, rec);
        // Required by the issue: 1e-5 relative. Float intersection error is ~1e-6 here.
        ASSERT_LT(glm::length(glm::dvec3(rebuilt) - analytic), 1e-5 * glm::length(analytic))
            << "eye " << e << " pixel " << x << "," << y;
        ++checked;
      }
  EXPECT_GT(checked, 2 * 40 * 32 / 2);
}

// The sub-pixel column where the world-space hit points cross x = 0 on row y.
double crossingColumn(const Scene& scene, const gl::GBufferImage& img, const EyeCamera& cam,
                      int y) {
  auto worldX = [&](int x) {
    const glm::uvec4 v = img.visibility[img.index(x, y)];
    return double(
        rebuildHitPoint(scene, {v.x, v.y, glm::uintBitsToFloat(v.z), glm::uintBitsToFloat(v.w)}).x);
  };
  for (int x = 0; x + 1 < img.width; ++x) {
    const double a = worldX(x), b = worldX(x + 1);
    if (a <= 0.0 && b > 0.0) return x + 0.5 + cam.jitter.x + (0.0 - a) / (b - a);
  }
  return -1.0;
}

TEST(GBuffer, StereoDisparityMatchesIpdAndFocalGeometry) {
  const float distance = 1.5f;
  const int w = 96, h = 16;
  const auto eyes = stereoEyes(w, h);
  const Scene scene = wallScene(distance);
  const Rendered r = renderGBuffer(scene, eyes);
  // Head-space point (0, y, -D) seen from an eye at x = +-ipd/2 has tangent -+ipd/(2D);
  // its column is (tan + left) / (left + right) * width.
  auto column = [&](const EyeCamera& c, float eyeX) {
    return (-eyeX / distance + c.fov.left) / (c.fov.left + c.fov.right) * w;
  };
  const double expectedL = column(eyes[0], -kDefaultIpd / 2),
               expectedR = column(eyes[1], kDefaultIpd / 2);
  const double measuredL = crossingColumn(scene, r.eye[0], eyes[0], h / 2);
  const double measuredR = crossingColumn(scene, r.eye[1], eyes[1], h / 2);
  // The plane is flat, so world x is linear in the column: the interpolated crossing is
  // exact up to float rounding of the hit points (~1e-6 m over 3 cm per pixel).
  EXPECT_NEAR(measuredL, expectedL, 1e-3);
  EXPECT_NEAR(measuredR, expectedR, 1e-3);
  EXPECT_NEAR(measuredL - measuredR, expectedL - expectedR, 2e-3);
}

TEST(GBuffer, NormalsBaseColourAndMaterialComeBackAsWritten) {
  const glm::vec3 color(0.2f, 0.5f, 0.8f);
  const Rendered r = renderGBuffer(wallScene(2.0f, color), stereoEyes(16, 16));
  for (int e = 0; e < 2; ++e)
    for (size_t i = 0; i < r.eye[e].normal.size(); ++i) {
      const glm::vec4 n = r.eye[e].normal[i], b = r.eye[e].baseColor[i], m = r.eye[e].material[i];
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(b[c], color[c], kHalfRel * color[c]);
      ASSERT_NEAR(n.z, 1.0f, kHalfRel);
      ASSERT_NEAR(n.x, 0.0f, kHalfRel);
      ASSERT_NEAR(m.x, 0.25f, kHalfRel * 0.25f);       // metallic
      ASSERT_NEAR(m.y, 0.75f, kHalfRel * 0.75f);       // roughness
      ASSERT_EQ(r.eye[e].motion[i], glm::vec2(0.0f));  // static scene, static camera
    }
}

// The hybrid frame reads back the visibility records alone (all its tracer reads): they
// must be the full read's, bit for bit, through both read paths, and the other targets
// empty, so that nothing can read a stale one.
TEST(GBuffer, VisibilityReadBackIsTheFullReadsRecordsAndNothingElse) {
  osmesaContext();
  const Scene scene = wallScene(2.0f);
  gl::SceneGpu gpu(scene);
  const auto eyes = stereoEyes(24, 20);
  gl::GBufferPass pass(24, 20);
  pass.render(gpu, eyes,
              {eyes[0].unjitteredProjection() * eyes[0].view(),
               eyes[1].unjitteredProjection() * eyes[1].view()});
  std::array<gl::GBufferImage, 2> full, sync, pbo;
  gl::GBufferReadback all(pass), visibility(pass, gl::GBufferRead::Visibility);
  all.start(2);
  all.finish(full);
  visibility.start(2);
  visibility.finish(pbo);
  for (int e = 0; e < 2; ++e) {
    sync[e] = full[e];  // storage with every target filled, as a reused image has
    pass.read(e, sync[e], gl::GBufferRead::Visibility);
    ASSERT_EQ(full[e].visibility.size(), size_t(24 * 20));
    ASSERT_NE(full[e].normal.size(), 0u);
    for (const gl::GBufferImage* g : {&sync[e], &pbo[e]}) {
      EXPECT_EQ(g->width, 24);
      EXPECT_EQ(g->height, 20);
      EXPECT_EQ(g->visibility, full[e].visibility);
      EXPECT_TRUE(g->normal.empty() && g->baseColor.empty() && g->material.empty() &&
                  g->emission.empty() && g->motion.empty() && g->depth.empty());
    }
  }
}

TEST(GBuffer, OneDrawCallPerMeshCoversBothEyesAndAllInstances) {
  Scene scene = wallScene(5.0f);
  scene.meshes.push_back(rectangleMesh(0.1f, 0.1f, 0));
  scene.meshes.push_back(rectangleMesh(0.2f, 0.1f, 0));
  for (int i = 0; i < 3; ++i) {
    Instance inst;
    inst.mesh = 1;
    inst.transform = glm::translate(glm::mat4(1.0f), glm::vec3(-0.5f + 0.5f * i, 0, -2));
    scene.instances.push_back(inst);
  }
  scene.instances.push_back(
      {2, glm::translate(glm::mat4(1.0f), glm::vec3(0, 0.4f, -2)), glm::mat4(1.0f), ""});
  const Rendered r = renderGBuffer(scene, stereoEyes(32, 32));
  EXPECT_EQ(r.stats.drawCalls, 3u);       // three meshes, not six
  EXPECT_EQ(r.stats.instances, 2u * 5u);  // every scene instance once per eye
  // Each of mesh 1's instances shows up in both eyes with its own id.
  for (int e = 0; e < 2; ++e)
    for (uint32_t id = 1; id <= 4; ++id) {
      bool seen = false;
      for (const glm::uvec4& v : r.eye[e].visibility) seen |= v.x == id;
      EXPECT_TRUE(seen) << "instance " << id << " eye " << e;
    }
}

}  // namespace
}  // namespace photovr
