// G-buffer behaviour per glTF material feature: alpha MASK, back-face culling and
// double-sided materials, mirrored instances, textures with sRGB decoding and transforms,
// motion vectors, and the side-by-side fallback routing.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "core/image_io.h"
#include "gl/gbuffer.h"
#include "tests/gl/gl_test_util.h"

namespace photovr {
namespace {

using testing::osmesaContext;
using testing::plainMaterial;
using testing::rectangleMesh;

constexpr float kHalfRel = 1.0f / 2048.0f;  // half-float rounding, 11 significant bits

struct Frame {
  gl::GBufferImage eye[2];
};

Frame render(const Scene& scene, const EyeCamera& cam,
             gl::EyeRouting routing = gl::EyeRouting::Layered,
             const std::array<glm::mat4, 2>* previous = nullptr) {
  osmesaContext();  // makes it current
  gl::SceneGpu gpu(scene);
  gl::GBufferPass pass(cam.width, cam.height, routing);
  const glm::mat4 vp = cam.unjitteredProjection() * cam.view();
  pass.render(gpu, {cam, cam}, previous ? *previous : std::array<glm::mat4, 2>{vp, vp});
  return {{pass.read(0), pass.read(1)}};
}

EyeCamera monoCamera(int w, int h) {
  EyeCamera c;
  c.fov = FovTangents::symmetric(1.0f, float(w) / h);
  c.width = w;
  c.height = h;
  return c;
}

Scene singleRectangle(Material material, glm::mat4 transform) {
  Scene s;
  s.materials.push_back(material);
  s.meshes.push_back(rectangleMesh(1.0f, 1.0f, 0));
  s.instances.push_back({0, transform, transform, "r"});
  return s;
}

size_t covered(const gl::GBufferImage& img) {
  size_t n = 0;
  for (const glm::uvec4& v : img.visibility) n += v.x != kNoHitInstance;
  return n;
}

const glm::mat4 kInFront = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -1));
const glm::mat4 kFacingAway = glm::rotate(kInFront, float(M_PI), glm::vec3(0, 1, 0));

TEST(GBufferFeatures, SingleSidedBackFacesAreCulled) {
  const Frame f =
      render(singleRectangle(plainMaterial(glm::vec3(1)), kFacingAway), monoCamera(16, 16));
  EXPECT_EQ(covered(f.eye[0]), 0u);
}

TEST(GBufferFeatures, DoubleSidedBackFacesShowWithTheNormalFlipped) {
  Material m = plainMaterial(glm::vec3(1));
  m.doubleSided = true;
  const Frame f = render(singleRectangle(m, kFacingAway), monoCamera(16, 16));
  ASSERT_EQ(covered(f.eye[0]), 16u * 16u);
  // The rectangle's normal points to -Z after the turn; the viewer's side is +Z.
  for (const glm::vec4& n : f.eye[0].normal) ASSERT_NEAR(n.z, 1.0f, kHalfRel);
}

TEST(GBufferFeatures, MirroredInstanceOfASingleSidedMeshStaysVisibleFromItsFront) {
  // Scaling x by -1 reverses the winding but not which side the normal faces.
  const glm::mat4 mirrored = glm::scale(kInFront, glm::vec3(-1, 1, 1));
  const Frame f =
      render(singleRectangle(plainMaterial(glm::vec3(1)), mirrored), monoCamera(16, 16));
  EXPECT_EQ(covered(f.eye[0]), 16u * 16u);
}

Texture checkerAlpha() {
  Texture t;
  t.name = "alpha";
  t.width = t.height = 2;
  t.nearest = true;
  // Left column opaque, right column transparent.
  t.rgba = {255, 255, 255, 255, 255, 255, 255, 0, 255, 255, 255, 255, 255, 255, 255, 0};
  return t;
}

TEST(GBufferFeatures, AlphaMaskDiscardsBelowTheCutoff) {
  Material m = plainMaterial(glm::vec3(1));
  m.alphaMode = AlphaMode::Mask;
  m.baseColorTexture.texture = 0;
  Scene s = singleRectangle(m, kInFront);
  s.textures.push_back(checkerAlpha());
  const Frame f = render(s, monoCamera(16, 16));
  const gl::GBufferImage& img = f.eye[0];
  // The rectangle fills the view (tan 0.5 at 1 m < 1 m half-size); uv.x = 0.5 at the centre.
  for (int y = 0; y < 16; ++y) {
    EXPECT_NE(img.visibility[img.index(2, y)].x, kNoHitInstance);
    EXPECT_EQ(img.visibility[img.index(13, y)].x, kNoHitInstance) << "row " << y;
  }
  Scene opaque = s;
  opaque.materials[0].alphaMode = AlphaMode::Opaque;  // the same texture, mask ignored
  EXPECT_EQ(covered(render(opaque, monoCamera(16, 16)).eye[0]), 16u * 16u);
}

TEST(GBufferFeatures, BaseColourTextureIsSrgbDecodedAndTransformed) {
  Texture t;
  t.name = "two";
  t.width = 2;
  t.height = 1;
  t.nearest = true;
  t.rgba = {128, 128, 128, 255, 255, 0, 0, 255};  // left grey (sRGB 128), right red
  Material m = plainMaterial(glm::vec3(1));
  m.baseColorTexture.texture = 0;
  // KHR_texture_transform scale 0.5 maps the whole rectangle to the left texel.
  m.baseColorTexture.transform.scale = glm::vec2(0.5f, 1.0f);
  Scene s = singleRectangle(m, kInFront);
  s.textures.push_back(t);
  const Frame f = render(s, monoCamera(8, 8));
  const float grey = srgbToLinear(128.0f / 255.0f);  // 0.2158
  for (const glm::vec4& c : f.eye[0].baseColor) {
    // sRGB8 decode is exact to 8-bit table precision, then half-float storage.
    ASSERT_NEAR(c.r, grey, 2.0f * kHalfRel * grey + 1e-3f);
    ASSERT_NEAR(c.g, grey, 2.0f * kHalfRel * grey + 1e-3f);
  }
}

TEST(GBufferFeatures, MotionVectorsPointToLastFramesPixel) {
  const EyeCamera cam = monoCamera(32, 32);
  Scene s = singleRectangle(plainMaterial(glm::vec3(1)), glm::scale(kInFront, glm::vec3(5)));
  // Last frame the camera sat 0.1 m further right: a point now at the centre was then
  // left of it by focal * 0.1 / 1 pixels.
  EyeCamera before = cam;
  before.pose.position.x = 0.1f;
  const std::array<glm::mat4, 2> prev = {before.unjitteredProjection() * before.view(),
                                         before.unjitteredProjection() * before.view()};
  const Frame f = render(s, cam, gl::EyeRouting::Layered, &prev);
  const float focalPx = cam.width / (cam.fov.left + cam.fov.right);
  for (const glm::vec2& m : f.eye[0].motion) {
    // Half-float storage of ~2.9 px: 2^-11 relative.
    ASSERT_NEAR(m.x, -0.1f * focalPx, 4.0f * kHalfRel * 0.1f * focalPx);
    ASSERT_NEAR(m.y, 0.0f, 1e-3f);
  }
}

// Issue 23: an animated object's motion, not the camera's. The rectangle's node moves +x at
// 1 m/s (a linear translation channel); posed at 0.5 s with the previous pose at 0.4 s, a
// point now at the centre was 0.1 m to the left a frame ago, focal * 0.1 / 1 pixels.
// Node 0 (scale 5) moving from (0, 0, -1) along +x at 1 m/s, posed at 0.5 s after 0.4 s.
void addMovingNodeAndPose(Scene& s, std::vector<int> instances) {
  SceneNode node;
  node.scale = glm::dvec3(5.0);
  node.instances = std::move(instances);
  s.nodes.push_back(node);
  AnimationChannel move;
  move.node = 0;
  move.path = AnimationPath::Translation;
  move.times = {0.0f, 2.0f};
  move.values = {{0, 0, -1, 0}, {2, 0, -1, 0}};
  s.animations.push_back({"move", {move}});
  poseScene(s, 0.5, 0.4);
}

TEST(GBufferFeatures, AnimatedObjectsMotionVectorsPointToLastFramesPixel) {
  const EyeCamera cam = monoCamera(32, 32);
  Scene s = singleRectangle(plainMaterial(glm::vec3(1)), glm::mat4(1.0f));
  addMovingNodeAndPose(s, {0});
  const Frame f = render(s, cam);
  const float focalPx = cam.width / (cam.fov.left + cam.fov.right);
  for (const glm::vec2& m : f.eye[0].motion) {
    // Half-float storage of ~2.9 px: 2^-11 relative; the poses' float rounding is far below.
    ASSERT_NEAR(m.x, -0.1f * focalPx, 4.0f * kHalfRel * 0.1f * focalPx);
    ASSERT_NEAR(m.y, 0.0f, 1e-3f);
  }
}

// The same motion by a skin: the rectangle's vertices follow one joint that moves as the
// node above did, the instance stays at identity, so only the skinned previous positions
// (a vertex attribute) can carry it.
TEST(GBufferFeatures, SkinnedMotionVectorsPointToLastFramesPixel) {
  const EyeCamera cam = monoCamera(32, 32);
  Scene s = singleRectangle(plainMaterial(glm::vec3(1)), glm::mat4(1.0f));
  Mesh& mesh = s.meshes[0];
  mesh.skinning.skin = 0;
  mesh.skinning.positions = mesh.positions;
  mesh.skinning.normals = mesh.normals;
  mesh.skinning.joints.assign(mesh.vertexCount(), glm::u16vec4(0));
  mesh.skinning.weights.assign(mesh.vertexCount(), glm::vec4(1, 0, 0, 0));
  s.skins.push_back({"one", {0}, {glm::dmat4(1.0)}});
  addMovingNodeAndPose(s, {});  // the joint, carrying no instance
  ASSERT_EQ(s.instances[0].transform, glm::mat4(1.0f));
  const Frame f = render(s, cam);
  const float focalPx = cam.width / (cam.fov.left + cam.fov.right);
  ASSERT_GT(covered(f.eye[0]), 0u);
  for (size_t i = 0; i < f.eye[0].motion.size(); ++i) {
    if (f.eye[0].visibility[i].x == kNoHitInstance) continue;
    const glm::vec2 m = f.eye[0].motion[i];
    ASSERT_NEAR(m.x, -0.1f * focalPx, 4.0f * kHalfRel * 0.1f * focalPx);
    ASSERT_NEAR(m.y, 0.0f, 1e-3f);
  }
}

TEST(GBufferFeatures, SideBySideFallbackMatchesLayeredRouting) {
  StereoRig rig;
  Scene s = singleRectangle(plainMaterial(glm::vec3(0.3f, 0.6f, 0.9f)),
                            glm::rotate(kInFront, 0.5f, glm::vec3(1, 1, 0)));
  const std::array<EyeCamera, 2> eyes = {rig.eye(Eye::Left, 40, 30, {0.2f, 0.1f}),
                                         rig.eye(Eye::Right, 40, 30, {0.2f, 0.1f})};
  gl::Context& ctx = osmesaContext();
  ASSERT_TRUE(ctx.hasExtension("GL_ARB_shader_viewport_layer_array"));
  gl::SceneGpu gpu(s);
  const std::array<glm::mat4, 2> vp = {eyes[0].unjitteredProjection() * eyes[0].view(),
                                       eyes[1].unjitteredProjection() * eyes[1].view()};
  gl::GBufferPass layered(40, 30, gl::EyeRouting::Layered);
  gl::GBufferPass sbs(40, 30, gl::EyeRouting::SideBySide);
  layered.render(gpu, eyes, vp);
  sbs.render(gpu, eyes, vp);
  for (int e = 0; e < 2; ++e) {
    const gl::GBufferImage a = layered.read(e), b = sbs.read(e);
    size_t differ = 0;
    for (size_t i = 0; i < a.visibility.size(); ++i)
      differ += a.visibility[i].x != b.visibility[i].x;
    // Squeezing x by 0.5 changes edge rounding only: at most one pixel per edge row.
    EXPECT_LE(differ, 2u * 30u) << "eye " << e;
    EXPECT_GT(covered(a), 100u);
  }
}

}  // namespace
}  // namespace photovr
