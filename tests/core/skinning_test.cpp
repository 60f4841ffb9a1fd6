// Skins (issue 23): a loaded skinned glTF file deformed by linear-blend skinning, checked
// against vertex positions and normals worked out by hand for a two-joint bar, and the
// loader's refusals of skin data it cannot use.
#include "core/skinning.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "core/error.h"
#include "core/gltf_loader.h"
#include "core/scene.h"
#include "tests/core/skinned_glb.h"
#include "tests/core/test_dir.h"

namespace photovr {
namespace {

// Float vertex data skinned in double and stored as float: a few ulps of values near 2.
constexpr float kTolerance = 1e-6f;

using testing::SkinOptions;

std::string skinnedFile(const SkinOptions& o = {}) {
  return testing::skinnedFile(testing::freshTestDir("photovr_skinning"), o);
}

void expectNear(const glm::vec3& actual, const glm::vec3& expected, const char* what) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], kTolerance) << what << " " << c;
}

const Mesh& skinnedMesh(const Scene& s) {
  for (const Instance& i : s.instances)
    if (s.meshes[size_t(i.mesh)].skinned()) return s.meshes[size_t(i.mesh)];
  throw std::runtime_error("no skinned mesh");
}

TEST(Skinning, RestPoseIgnoresTheSkinnedNodesOwnTransform) {
  const Scene s = loadGltf(skinnedFile());
  ASSERT_EQ(s.skins.size(), 1u);
  EXPECT_EQ(s.skins[0].joints.size(), 2u);
  for (const std::string& w : s.warnings) EXPECT_EQ(w.find("skin"), std::string::npos) << w;
  const Mesh& m = skinnedMesh(s);
  // The joints' rest pose is the bind pose (inverse binds invert it): the bar as stored,
  // not 100 m away where the skinned node's translation would put it.
  expectNear(m.positions[1], {2, 0, 0}, "B");
  expectNear(m.positions[2], {1, 1, 0}, "C");
  EXPECT_EQ(s.instances[0].transform, glm::mat4(1.0f));
}

// At t the tip has turned by a = 90 t degrees about its joint at (1,0,0): M1 = T R(a) T^-1.
TEST(Skinning, PosedVerticesBlendTheirJointsMatrices) {
  Scene s = loadGltf(skinnedFile());
  for (double t : {0.5, 1.0}) {
    poseScene(s, t, t);
    const Mesh& m = skinnedMesh(s);
    const float a = float(t * M_PI / 2), c = std::cos(a), sn = std::sin(a);
    const auto tip = [&](glm::vec3 p) {  // R(a) about (1,0,0)
      const glm::vec3 r = p - glm::vec3(1, 0, 0);
      return glm::vec3(1 + c * r.x - sn * r.y, sn * r.x + c * r.y, r.z);
    };
    expectNear(m.positions[0], {0, 0, 0}, "A: root only");
    expectNear(m.positions[1], tip({2, 0, 0}), "B: tip only");
    expectNear(m.positions[3], tip({2, 1, 0}), "D: tip only");
    expectNear(m.positions[2], 0.5f * (glm::vec3(1, 1, 0) + tip({1, 1, 0})), "C: half each");
    // Normals: B's turns with the tip; C's by the inverse transpose of 0.5 (I + R(a)), a
    // rotation by a / 2 times a scale, so +x turns by a / 2.
    expectNear(m.normals[1], {c, sn, 0}, "B normal");
    expectNear(m.normals[2], {std::cos(a / 2), std::sin(a / 2), 0}, "C normal");
  }
}

// The motion vectors' previous positions: skinned at the previous time, or, in a played
// sequence, the last pose's positions kept; both the same floats.
TEST(Skinning, PreviousPositionsAreThePreviousPoseWhetherKeptOrSkinned) {
  Scene played = loadGltf(skinnedFile());
  poseScene(played, 0.3, 0.2);
  const std::vector<glm::vec3> at03 = skinnedMesh(played).positions;
  poseScene(played, 0.5, 0.3);  // kept: the mesh was posed at 0.3
  EXPECT_EQ(skinnedMesh(played).skinning.previousPositions, at03);
  Scene fresh = loadGltf(skinnedFile());
  poseScene(fresh, 0.5, 0.3);  // skinned at 0.3
  EXPECT_EQ(skinnedMesh(fresh).skinning.previousPositions, at03);
  EXPECT_EQ(skinnedMesh(fresh).positions, skinnedMesh(played).positions);
  EXPECT_NE(at03, skinnedMesh(played).positions);  // it moved
}

TEST(Skinning, AMeshAlsoUsedRigidlyIsSkinnedOnACopy) {
  SkinOptions o;
  o.rigidUserToo = true;
  Scene s = loadGltf(skinnedFile(o));
  ASSERT_EQ(s.meshes.size(), 2u);
  poseScene(s, 1.0, 1.0);
  const Instance& rigid = s.instances.back();
  EXPECT_FALSE(s.meshes[size_t(rigid.mesh)].skinned());
  expectNear(s.meshes[size_t(rigid.mesh)].positions[1], {2, 0, 0}, "rigid B stays");
  EXPECT_FLOAT_EQ(rigid.transform[3][2], 5.0f);
  expectNear(skinnedMesh(s).positions[1], {1, 1, 0}, "skinned B turned");
}

void expectLoadError(const std::string& path, const std::string& message) {
  try {
    loadGltf(path);
    FAIL() << "loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
  }
}

TEST(Skinning, JointIndexBeyondTheSkinIsAnError) {
  SkinOptions o;
  o.tipJointOfD = 7;
  expectLoadError(skinnedFile(o), "JOINTS_0: vertex 3 names joint 7 of a skin with 2");
}

TEST(Skinning, NegativeOrMissingWeightsAreAnError) {
  for (float w : {-1.0f, 0.0f, std::nanf("")}) {
    SkinOptions o;
    o.weightOfA = w;
    expectLoadError(skinnedFile(o), "WEIGHTS_0: vertex 0 has negative, non-finite or no weights");
  }
}

}  // namespace
}  // namespace photovr
