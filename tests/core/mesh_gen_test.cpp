#include "core/mesh_gen.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "core/mesh_util.h"

namespace photovr {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Float positions carry ~6e-8 relative rounding; sums over a few thousand triangles stay
// well inside 1e-5 relative, so "exact" comparisons below use that.
constexpr double kFloatRel = 1e-5;

// Every triangle's winding (counter-clockwise = front) must agree with its vertex normals,
// and every normal must be unit length: shading and back-face culling rely on both.
void expectWindingMatchesNormals(const Mesh& m) {
  ASSERT_EQ(m.normals.size(), m.positions.size());
  for (const glm::vec3& n : m.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f);
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    const uint32_t* i = &m.indices[3 * t];
    const glm::vec3 a = m.positions[i[0]], b = m.positions[i[1]], c = m.positions[i[2]];
    const glm::vec3 face = glm::cross(b - a, c - a);
    const glm::vec3 avg = m.normals[i[0]] + m.normals[i[1]] + m.normals[i[2]];
    ASSERT_GT(glm::dot(face, avg), 0.0f) << m.name << " triangle " << t;
  }
}

void expectValid(const Mesh& m) {
  EXPECT_NO_THROW(validateMesh(m, "generated"));
  EXPECT_EQ(degenerateTriangleCount(m), 0u) << m.name;
  EXPECT_EQ(m.uv0.size(), m.positions.size());
  expectWindingMatchesNormals(m);
}

TEST(MeshGen, QuadFacesAlongCrossOfItsEdges) {
  const Mesh q = makeQuad({0, 0, 0}, {2, 0, 0}, {0, 3, 0});
  expectValid(q);
  EXPECT_EQ(q.triangleCount(), 2u);
  EXPECT_NEAR(meshSurfaceArea(q), 6.0, 6.0 * kFloatRel);
  for (const glm::vec3& n : q.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
}

TEST(MeshGen, BoxIsClosedOutwardWithExactAreaAndVolume) {
  const Mesh box = makeBox({-1, 0, -2}, {1, 3, 2});  // 2 x 3 x 4
  expectValid(box);
  EXPECT_EQ(box.triangleCount(), 12u);
  EXPECT_NEAR(meshSurfaceArea(box), 2 * (6 + 12 + 8), 52 * kFloatRel);
  EXPECT_NEAR(meshSignedVolume(box), 24.0, 24 * kFloatRel);  // positive: outward
}

TEST(MeshGen, SphereAreaAndVolumeWithinTessellationBounds) {
  const float r = 2.0f;
  const int segments = 64, rings = 32;
  const Mesh s = makeUvSphere(r, segments, rings);
  expectValid(s);
  EXPECT_EQ(s.triangleCount(), size_t(segments * (2 * rings - 2)));  // pole rows are fans
  // The tessellation is convex with every vertex on the sphere, so it lies between the
  // sphere and the sphere of radius r cos(delta), delta bounding a face's angular
  // circumradius (the cell's angular diagonal is an upper bound). Area and volume are
  // monotone under inclusion of convex bodies.
  const double delta = std::hypot(kPi / rings, 2 * kPi / segments);
  const double c = std::cos(delta);
  const double area = 4 * kPi * r * r, volume = 4.0 / 3.0 * kPi * r * r * r;
  EXPECT_LE(meshSurfaceArea(s), area * (1 + kFloatRel));
  EXPECT_GE(meshSurfaceArea(s), area * c * c);
  EXPECT_LE(meshSignedVolume(s), volume * (1 + kFloatRel));
  EXPECT_GE(meshSignedVolume(s), volume * c * c * c);
}

TEST(MeshGen, CylinderMatchesItsInscribedPrism) {
  const float r = 0.5f, h = 3.0f;
  const int n = 48;
  const Mesh cyl = makeCylinder(r, h, n, 5, true);
  expectValid(cyl);
  // The tessellation is exactly the prism over the inscribed n-gon: side n * 2r sin(pi/n)
  // * h, caps n/2 r^2 sin(2pi/n). Its relative deficit from the circle is
  // 1 - sin(x)/x ~ x^2/6 with x = 2pi/n (0.29 % here), bounded below with that term.
  const double polygon = 0.5 * n * r * r * std::sin(2 * kPi / n);
  const double side = n * 2 * r * std::sin(kPi / n) * h;
  EXPECT_NEAR(meshSurfaceArea(cyl), side + 2 * polygon, (side + 2 * polygon) * kFloatRel);
  EXPECT_NEAR(meshSignedVolume(cyl), polygon * h, polygon * h * kFloatRel);
  const double x = 2 * kPi / n;
  EXPECT_NEAR(meshSignedVolume(cyl), kPi * r * r * h, kPi * r * r * h * x * x / 6);
}

TEST(MeshGen, OpenCylinderHasOnlyItsSide) {
  const Mesh cyl = makeCylinder(1.0f, 1.0f, 16, 3, false);
  expectValid(cyl);
  EXPECT_EQ(cyl.triangleCount(), size_t(16 * 3 * 2));
}

TEST(MeshGen, ArchIsAClosedHalfAnnulusPrism) {
  const float r0 = 1.7f, t = 0.3f, depth = 0.6f;
  const int n = 64;
  const Mesh arch = makeArch(r0, t, depth, n);
  expectValid(arch);
  const double r1 = r0 + t;
  // Front face = n sectors of the inscribed polygons: n/2 (r1^2 - r0^2) sin(pi/n); the
  // analytic half annulus differs by 1 - sin(x)/x ~ x^2/6, x = pi/n (0.04 % here).
  const double front = 0.5 * n * (r1 * r1 - r0 * r0) * std::sin(kPi / n);
  EXPECT_NEAR(meshSignedVolume(arch), front * depth, front * depth * kFloatRel);
  const double analytic = 0.5 * kPi * (r1 * r1 - r0 * r0) * depth;
  const double x = kPi / n;
  EXPECT_NEAR(meshSignedVolume(arch), analytic, analytic * x * x / 6);
  Bounds b;
  for (const glm::vec3& p : arch.positions) b.extend(p);
  EXPECT_NEAR(b.min.y, 0.0f, 1e-6f);
  EXPECT_NEAR(b.max.y, r1, 1e-5f);
  EXPECT_NEAR(b.max.z - b.min.z, depth, 1e-6f);
}

TEST(MeshGen, TransformKeepsWindingAndUnitNormalsEvenWhenMirrored) {
  Mesh s = makeUvSphere(1.0f, 16, 8);
  transformMesh(s, glm::scale(glm::mat4(1.0f), {-2.0f, 1.0f, 0.5f}));
  expectWindingMatchesNormals(s);
  EXPECT_GT(meshSignedVolume(s), 0.0);  // still outward after the mirror
}

TEST(MeshGen, FlipTurnsABoxIntoARoom) {
  Mesh room = makeBox({0, 0, 0}, {1, 1, 1});
  flipMesh(room);
  expectWindingMatchesNormals(room);
  EXPECT_NEAR(meshSignedVolume(room), -1.0, kFloatRel);
}

TEST(MeshGen, AppendOffsetsIndicesAndKeepsSharedAttributes) {
  Mesh a = makeQuad({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const Mesh b = makeQuad({0, 0, 1}, {1, 0, 0}, {0, 1, 0});
  appendMesh(a, b);
  expectValid(a);
  EXPECT_EQ(a.vertexCount(), 8u);
  EXPECT_EQ(a.indices[6], 4u);
}

}  // namespace
}  // namespace photovr
