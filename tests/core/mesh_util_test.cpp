#include "core/mesh_util.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/error.h"

namespace photovr {
namespace {

Mesh unitTriangle() {
  Mesh m;
  m.name = "tri";
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.indices = {0, 1, 2};
  return m;
}

std::string errorOf(const Mesh& m) {
  try {
    validateMesh(m, "file.gltf");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ValidateMesh, AcceptsAValidTriangle) {
  EXPECT_EQ(errorOf(unitTriangle()), "");
}

TEST(ValidateMesh, RejectsNaNPositionNamingFileMeshAndVertex) {
  Mesh m = unitTriangle();
  m.positions[1].y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(errorOf(m), "file.gltf: mesh 'tri': non-finite POSITION at vertex 1");
}

TEST(ValidateMesh, RejectsInfiniteNormal) {
  Mesh m = unitTriangle();
  m.normals.assign(3, glm::vec3(0, 0, 1));
  m.normals[2].z = std::numeric_limits<float>::infinity();
  EXPECT_NE(errorOf(m).find("non-finite NORMAL at vertex 2"), std::string::npos);
}

TEST(ValidateMesh, RejectsOutOfRangeIndex) {
  Mesh m = unitTriangle();
  m.indices[2] = 7;
  EXPECT_NE(errorOf(m).find("index 7 at position 2 is out of range (3 vertices)"),
            std::string::npos);
}

TEST(ValidateMesh, RejectsMeshWhoseTrianglesAllHaveZeroArea) {
  Mesh m = unitTriangle();
  m.positions[2] = {2, 0, 0};  // collinear
  EXPECT_NE(errorOf(m).find("every triangle has zero area"), std::string::npos);
}

TEST(ValidateMesh, AcceptsSomeDegenerateTrianglesAmongGoodOnes) {
  Mesh m = unitTriangle();
  m.indices.insert(m.indices.end(), {0, 0, 1});
  EXPECT_EQ(errorOf(m), "");
  EXPECT_EQ(degenerateTriangleCount(m), 1u);
}

TEST(ValidateMesh, RejectsIndexCountNotMultipleOfThree) {
  Mesh m = unitTriangle();
  m.indices.push_back(0);
  EXPECT_NE(errorOf(m).find("not a multiple of 3"), std::string::npos);
}

TEST(MeshNormals, FlatShadingGivesTheFaceNormal) {
  Mesh m = unitTriangle();
  makeFlatShaded(m);
  for (const glm::vec3& n : m.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
}

TEST(MeshTangents, FollowUGradientAndAreOrthogonalToNormal) {
  Mesh m = unitTriangle();
  m.uv0 = {{0, 0}, {1, 0}, {0, 1}};
  computeVertexNormals(m);
  computeTangents(m);
  ASSERT_EQ(m.tangents.size(), 3u);
  for (const glm::vec4& t : m.tangents) {
    // Exact in this configuration up to float rounding of a unit vector.
    EXPECT_NEAR(t.x, 1.0f, 1e-6f);
    EXPECT_NEAR(t.y, 0.0f, 1e-6f);
    EXPECT_NEAR(t.z, 0.0f, 1e-6f);
    EXPECT_EQ(t.w, 1.0f);
  }
}

}  // namespace
}  // namespace photovr
