// glTF animations (issue 23): channels sampled as glTF 2.0 Appendix C defines them, checked
// against the formulas written out here, and a loaded file posed at a time against its
// node transforms composed by hand.
#include "core/animation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "core/gltf_loader.h"
#include "core/scene.h"
#include "tests/core/glb_file.h"
#include "tests/core/test_dir.h"

namespace photovr {
namespace {

namespace fs = std::filesystem;

// Float keys read back in double: a few float ulps of the values involved.
constexpr double kTolerance = 1e-6;

AnimationChannel channel(AnimationPath path, Interpolation interpolation, std::vector<float> times,
                         std::vector<glm::vec4> values) {
  AnimationChannel c;
  c.path = path;
  c.interpolation = interpolation;
  c.times = std::move(times);
  c.values = std::move(values);
  return c;
}

TEST(Animation, LinearTranslationIsTheLerpAndHoldsOutsideTheKeys) {
  const AnimationChannel c = channel(AnimationPath::Translation, Interpolation::Linear, {1, 3, 4},
                                     {{0, 0, 0, 0}, {2, 4, -6, 0}, {2, 0, 0, 0}});
  const glm::dvec4 mid = sampleChannel(c, 1.5);  // a quarter of the way from key 0 to key 1
  EXPECT_NEAR(mid.x, 0.5, kTolerance);
  EXPECT_NEAR(mid.y, 1.0, kTolerance);
  EXPECT_NEAR(mid.z, -1.5, kTolerance);
  EXPECT_NEAR(sampleChannel(c, 3.5).y, 2.0, kTolerance);      // halfway from key 1 to key 2
  EXPECT_EQ(sampleChannel(c, 0.0), glm::dvec4(0.0));          // before the first key: held
  EXPECT_EQ(sampleChannel(c, 9.0), glm::dvec4(2, 0, 0, 0));   // after the last: held
  EXPECT_EQ(sampleChannel(c, 3.0), glm::dvec4(2, 4, -6, 0));  // on a key: its value
}

TEST(Animation, StepHoldsEachKeyUntilTheNext) {
  const AnimationChannel c =
      channel(AnimationPath::Scale, Interpolation::Step, {0, 1}, {{1, 1, 1, 0}, {3, 3, 3, 0}});
  EXPECT_EQ(sampleChannel(c, 0.999).x, 1.0);
  EXPECT_EQ(sampleChannel(c, 1.0).x, 3.0);
}

// Linear rotation is the spherical interpolation: halfway from identity to 90 degrees about
// y is 45 degrees about y, along the shorter arc even when the keys' signs differ.
TEST(Animation, LinearRotationIsTheSlerpOnTheShorterArc) {
  const float h = float(std::sqrt(0.5));
  for (float sign : {1.0f, -1.0f}) {
    const AnimationChannel c = channel(AnimationPath::Rotation, Interpolation::Linear, {0, 2},
                                       {{0, 0, 0, 1}, {0, sign * h, 0, sign * h}});
    glm::dvec4 q = sampleChannel(c, 1.0);
    if (q.w < 0) q = -q;
    EXPECT_NEAR(q.y, std::sin(M_PI / 8), kTolerance) << sign;
    EXPECT_NEAR(q.w, std::cos(M_PI / 8), kTolerance) << sign;
  }
}

// Appendix C's cubic Hermite, written out for one interval: keys at t = 1 and 3 (td = 2),
// values 1 and 3, out-tangent of key 0 b0 = 4, in-tangent of key 1 a1 = -2, at s = 1/4.
TEST(Animation, CubicSplineIsAppendixCsHermite) {
  const std::vector<glm::vec4> values = {{9, 0, 0, 0},  {1, 0, 0, 0}, {4, 0, 0, 0},
                                         {-2, 0, 0, 0}, {3, 0, 0, 0}, {9, 0, 0, 0}};
  const AnimationChannel c =
      channel(AnimationPath::Translation, Interpolation::CubicSpline, {1, 3}, values);
  const double s = 0.25, td = 2.0;
  const double expected = (2 * s * s * s - 3 * s * s + 1) * 1 +
                          td * (s * s * s - 2 * s * s + s) * 4 + (-2 * s * s * s + 3 * s * s) * 3 +
                          td * (s * s * s - s * s) * -2;
  EXPECT_NEAR(sampleChannel(c, 1.5).x, expected, kTolerance);
  EXPECT_NEAR(sampleChannel(c, 1.0).x, 1.0, kTolerance);  // the keys' values, not tangents
  EXPECT_NEAR(sampleChannel(c, 3.0).x, 3.0, kTolerance);
}

// --- A file with an animation ---------------------------------------------------------------

template <typename T>
void append(std::string& b, std::initializer_list<T> values) {
  for (T v : values) b.append(reinterpret_cast<const char*>(&v), sizeof v);
}

// A triangle on node 1, child of node 0 (90 degrees about y). Node 1's translation is
// linear over keys 0 and 2 s, its rotation steps, its scale is a cubic spline.
struct AnimatedFile {
  std::string json, bin;
};

AnimatedFile animatedFile(float secondTime = 2.0f) {
  AnimatedFile f;
  append<float>(f.bin, {0, 0, 0, 1, 0, 0, 0, 1, 0});                   // 0: positions, 36
  append<uint16_t>(f.bin, {0, 1, 2, 0});                               // 1: indices, 6 (+2)
  append<float>(f.bin, {0, secondTime});                               // 2: times, 8
  append<float>(f.bin, {0, 0, 0, 2, 0, 4});                            // 3: translations, 24
  append<float>(f.bin, {0, 0, 0, 1, 0, 0, 0.70710678f, 0.70710678f});  // 4: rotations, 32
  append<float>(f.bin, {0, 0, 0, 1, 1, 1, 0.5f, 0.5f, 0.5f,            // 5: cubic scales, 72
                        0, 0, 0, 2, 2, 2, 0, 0, 0});
  f.json = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
"nodes":[{"rotation":[0,0.70710678,0,0.70710678],"children":[1]},{"mesh":0,"name":"mover"}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
"animations":[{"name":"move","channels":[
  {"sampler":0,"target":{"node":1,"path":"translation"}},
  {"sampler":1,"target":{"node":1,"path":"rotation"}},
  {"sampler":2,"target":{"node":1,"path":"scale"}}],
 "samplers":[{"input":2,"output":3},{"input":2,"output":4,"interpolation":"STEP"},
  {"input":2,"output":5,"interpolation":"CUBICSPLINE"}]}],
"buffers":[{"byteLength":)" +
           std::to_string(f.bin.size()) + R"(}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6},
 {"buffer":0,"byteOffset":44,"byteLength":8},{"buffer":0,"byteOffset":52,"byteLength":24},
 {"buffer":0,"byteOffset":76,"byteLength":32},{"buffer":0,"byteOffset":108,"byteLength":72}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
 {"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"},
 {"bufferView":2,"componentType":5126,"count":2,"type":"SCALAR","min":[0],"max":[2]},
 {"bufferView":3,"componentType":5126,"count":2,"type":"VEC3"},
 {"bufferView":4,"componentType":5126,"count":2,"type":"VEC4"},
 {"bufferView":5,"componentType":5126,"count":6,"type":"VEC3"}]})";
  return f;
}

std::string written(const AnimatedFile& f, const std::string& name) {
  const fs::path path = testing::freshTestDir("photovr_animation") / name;
  std::ofstream(path, std::ios::binary) << testing::glb(f.json, f.bin);
  return path.string();
}

// Node 1's world transform at time t, composed by hand from the keys above.
glm::dmat4 expectedPose(double t) {
  const double s = t / 2.0;
  const glm::dvec3 translation = s * glm::dvec3(2, 0, 4);       // linear
  const glm::dquat rotation = t < 2.0 ? glm::dquat(1, 0, 0, 0)  // step: key 0 until key 1
                                      : glm::dquat(std::sqrt(0.5), 0, 0, std::sqrt(0.5));
  const double h00 = 2 * s * s * s - 3 * s * s + 1, h10 = s * s * s - 2 * s * s + s,
               h01 = -2 * s * s * s + 3 * s * s;
  const double scale = h00 * 1 + 2.0 * h10 * 0.5 + h01 * 2;  // a1 = 0: no last term
  const glm::dmat4 parent = glm::mat4_cast(glm::dquat(std::sqrt(0.5), 0, std::sqrt(0.5), 0));
  return parent * glm::translate(glm::dmat4(1.0), translation) * glm::mat4_cast(rotation) *
         glm::scale(glm::dmat4(1.0), glm::dvec3(scale));
}

void expectNear(const glm::mat4& a, const glm::dmat4& b) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(double(a[c][r]), b[c][r], kTolerance) << c << r;
}

TEST(Animation, LoadedFilePosesItsNodesAtATime) {
  Scene s = loadGltf(written(animatedFile(), "animated.glb"));
  ASSERT_TRUE(isAnimated(s));
  ASSERT_EQ(s.animations.size(), 1u);
  EXPECT_EQ(s.animations[0].duration(), 2.0f);
  for (const std::string& w : s.warnings) EXPECT_EQ(w.find("not played"), std::string::npos) << w;
  poseScene(s, 0.5, 0.4);
  expectNear(s.instances[0].transform, expectedPose(0.5));
  expectNear(s.instances[0].previousTransform, expectedPose(0.4));  // for motion vectors
  // Looping: 2.5 s is 0.5 s into the second play.
  poseScene(s, 2.5, 2.5);
  expectNear(s.instances[0].transform, expectedPose(0.5));
}

TEST(Animation, KeyTimesThatDoNotIncreaseAreAnError) {
  const std::string path = written(animatedFile(0.0f), "still.glb");
  try {
    loadGltf(path);
    FAIL() << "loaded";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("still.glb: animation 'move' channel 0: key times must be finite and "
                        "strictly increasing"),
              std::string::npos)
        << what;
  }
}

}  // namespace
}  // namespace photovr
