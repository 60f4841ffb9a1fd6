#include "core/builtin_scenes.h"

#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/mesh_gen.h"
#include "core/mesh_util.h"

namespace photovr {
namespace {

using Triangle = std::array<glm::vec3, 3>;

std::vector<Triangle> worldTriangles(const Scene& scene, const std::string& nameContains = "") {
  std::vector<Triangle> out;
  for (const Instance& inst : scene.instances) {
    const Mesh& m = scene.meshes[inst.mesh];
    if (m.name.find(nameContains) == std::string::npos) continue;
    for (size_t t = 0; t < m.triangleCount(); ++t) {
      Triangle tri;
      for (int k = 0; k < 3; ++k)
        tri[k] = glm::vec3(inst.transform * glm::vec4(m.positions[m.indices[3 * t + k]], 1.0f));
      out.push_back(tri);
    }
  }
  return out;
}

// Möller-Trumbore; the nearest hit distance, if any. Brute force is fine at test sizes.
std::optional<float> nearestHit(const std::vector<Triangle>& tris, const glm::vec3& o,
                                const glm::vec3& d) {
  std::optional<float> best;
  for (const Triangle& t : tris) {
    const glm::vec3 e1 = t[1] - t[0], e2 = t[2] - t[0], p = glm::cross(d, e2);
    const float det = glm::dot(e1, p);
    if (std::abs(det) < 1e-12f) continue;
    const glm::vec3 s = o - t[0];
    const float u = glm::dot(s, p) / det;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(d, q) / det, dist = glm::dot(e2, q) / det;
    if (u < 0 || v < 0 || u + v > 1 || dist <= 0) continue;
    if (!best || dist < *best) best = dist;
  }
  return best;
}

// Fibonacci-sphere directions: even coverage without randomness.
std::vector<glm::vec3> sphereDirections(int n) {
  std::vector<glm::vec3> dirs;
  const float golden = 2.39996323f;
  for (int i = 0; i < n; ++i) {
    const float y = 1.0f - 2.0f * (i + 0.5f) / n, r = std::sqrt(1.0f - y * y);
    dirs.emplace_back(r * std::cos(golden * i), y, r * std::sin(golden * i));
  }
  return dirs;
}

int findMesh(const Scene& s, const std::string& name) {
  for (size_t i = 0; i < s.meshes.size(); ++i)
    if (s.meshes[i].name == name) return int(i);
  return -1;
}

const Material& materialOfMesh(const Scene& s, const std::string& name) {
  return s.materials[s.meshes[findMesh(s, name)].material];
}

const Instance& instanceOf(const Scene& s, const std::string& meshName) {
  const int m = findMesh(s, meshName);
  for (const Instance& inst : s.instances)
    if (inst.mesh == m) return inst;
  throw std::runtime_error("no instance of " + meshName);
}

float yRotationDegrees(const glm::mat4& m) {  // rotateY(a): column 0 = (cos a, 0, -sin a)
  return glm::degrees(std::atan2(-m[0][2], m[0][0]));
}

TEST(BuiltinScenes, NamesAreTheThreeScenes) {
  EXPECT_EQ(builtinSceneNames(), (std::vector<std::string>{"atrium", "cornell", "spheres"}));
  EXPECT_TRUE(isBuiltinScene("cornell"));
  EXPECT_FALSE(isBuiltinScene("sponza"));
}

TEST(BuiltinScenes, UnknownNameThrowsUsageErrorListingValidNames) {
  try {
    makeBuiltinScene("sponza");
    FAIL() << "no exception";
  } catch (const UsageError& e) {
    EXPECT_EQ(std::string(e.what()),
              "unknown built-in scene 'sponza' (valid: atrium, cornell, spheres)");
  }
}

class BuiltinEach : public testing::TestWithParam<std::string> {};

TEST_P(BuiltinEach, MeshesAreValidWithConsistentWindingAndUnitNormals) {
  const Scene s = makeBuiltinScene(GetParam());
  for (const Mesh& m : s.meshes) {
    EXPECT_NO_THROW(validateMesh(m, GetParam()));
    EXPECT_EQ(degenerateTriangleCount(m), 0u) << m.name;
    for (const glm::vec3& n : m.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f) << m.name;
    for (size_t t = 0; t < m.triangleCount(); ++t) {
      const uint32_t* i = &m.indices[3 * t];
      const glm::vec3 face =
          glm::cross(m.positions[i[1]] - m.positions[i[0]], m.positions[i[2]] - m.positions[i[0]]);
      ASSERT_GT(glm::dot(face, m.normals[i[0]] + m.normals[i[1]] + m.normals[i[2]]), 0.0f)
          << m.name << " triangle " << t;
    }
  }
}

TEST_P(BuiltinEach, IndicesAreInRangeAndTransformsKeepWinding) {
  const Scene s = makeBuiltinScene(GetParam());
  EXPECT_EQ(s.name, GetParam());
  for (const Mesh& m : s.meshes) {
    EXPECT_GE(m.material, 0);
    EXPECT_LT(size_t(m.material), s.materials.size());
  }
  for (const Instance& inst : s.instances) {
    ASSERT_GE(inst.mesh, 0);
    ASSERT_LT(size_t(inst.mesh), s.meshes.size());
    // A mirroring instance would turn front faces into back faces for the rasterizer.
    EXPECT_GT(glm::determinant(glm::mat3(inst.transform)), 0.0f) << inst.node;
    EXPECT_EQ(inst.transform, inst.previousTransform);  // static scene
  }
  for (const Material& m : s.materials)
    for (const TextureRef* r : {&m.baseColorTexture, &m.metallicRoughnessTexture, &m.normalTexture,
                                &m.occlusionTexture, &m.emissiveTexture})
      if (r->valid()) {
        EXPECT_LT(size_t(r->texture), s.textures.size()) << m.name;
      }
  for (const Texture& t : s.textures)
    EXPECT_EQ(t.rgba.size(), size_t(t.width) * t.height * 4) << t.name;
}

TEST_P(BuiltinEach, HasExactlyItsOwnView) {
  const Scene s = makeBuiltinScene(GetParam());
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.cameras[0].name, GetParam() + "-view");
  EXPECT_GT(s.cameras[0].yfov, glm::radians(30.0f));
  EXPECT_LT(s.cameras[0].yfov, glm::radians(90.0f));
  EXPECT_NEAR(glm::length(s.cameras[0].orientation), 1.0f, 1e-5f);
}

TEST_P(BuiltinEach, IsDeterministic) {
  const Scene a = makeBuiltinScene(GetParam()), b = makeBuiltinScene(GetParam());
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    EXPECT_EQ(a.meshes[i].positions, b.meshes[i].positions);
    EXPECT_EQ(a.meshes[i].normals, b.meshes[i].normals);
    EXPECT_EQ(a.meshes[i].uv0, b.meshes[i].uv0);
    EXPECT_EQ(a.meshes[i].indices, b.meshes[i].indices);
  }
  ASSERT_EQ(a.instances.size(), b.instances.size());
  for (size_t i = 0; i < a.instances.size(); ++i)
    EXPECT_EQ(a.instances[i].transform, b.instances[i].transform);
  ASSERT_EQ(a.textures.size(), b.textures.size());
  for (size_t i = 0; i < a.textures.size(); ++i) EXPECT_EQ(a.textures[i].rgba, b.textures[i].rgba);
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i)
    EXPECT_EQ(a.materials[i].baseColorFactor, b.materials[i].baseColorFactor);
}

INSTANTIATE_TEST_SUITE_P(Builtin, BuiltinEach, testing::Values("atrium", "cornell", "spheres"));

// ---------------------------------------------------------------------------------------
// cornell

TEST(BuiltinCornell, WallsAreWatertightAndFaceInwards) {
  const Scene s = makeBuiltinScene("cornell");
  const std::vector<Triangle> walls = worldTriangles(s, "wall");
  // Watertight and consistently wound: every directed edge is matched by its reverse once.
  std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> edges;
  const auto key = [](const glm::vec3& p) { return std::array<float, 3>{p.x, p.y, p.z}; };
  for (const Triangle& t : walls)
    for (int k = 0; k < 3; ++k) ++edges[{key(t[k]), key(t[(k + 1) % 3])}];
  for (const auto& [e, n] : edges) {
    EXPECT_EQ(n, 1);
    EXPECT_EQ(edges.count({e.second, e.first}), 1u);
  }
  Mesh all;
  for (const Triangle& t : walls) {
    const uint32_t base = uint32_t(all.positions.size());
    all.positions.insert(all.positions.end(), t.begin(), t.end());
    all.indices.insert(all.indices.end(), {base, base + 1, base + 2});
  }
  // 2 x 2 x 2 m, negative: the normals point into the box. Float corners are exact.
  EXPECT_NEAR(meshSignedVolume(all), -8.0, 1e-5);
}

TEST(BuiltinCornell, EveryRayFromInsideHitsSomething) {
  const Scene s = makeBuiltinScene("cornell");
  const std::vector<Triangle> tris = worldTriangles(s);
  for (const glm::vec3& o :
       {glm::vec3(0, 1, 0), glm::vec3(0, 1, 0.9f), glm::vec3(0.7f, 1.8f, -0.8f)})
    for (const glm::vec3& d : sphereDirections(2000)) {
      const std::optional<float> t = nearestHit(tris, o, d);
      ASSERT_TRUE(t.has_value()) << "ray escapes from " << o.x << "," << o.y << "," << o.z;
      EXPECT_LT(*t, 3.5f);  // the box diagonal
    }
}

TEST(BuiltinCornell, CameraIsInsideNearTheFrontLookingAtTheBack) {
  const Camera c = makeBuiltinScene("cornell").cameras[0];  // a copy: the scene is a temporary
  EXPECT_LT(glm::abs(c.position.x), 1.0f);
  EXPECT_GT(c.position.y, 0.0f);
  EXPECT_LT(c.position.y, 2.0f);
  EXPECT_GT(c.position.z, 0.5f);
  EXPECT_LT(c.position.z, 1.0f - c.znear);
  const glm::vec3 forward = c.orientation * glm::vec3(0, 0, -1);
  EXPECT_NEAR(forward.z, -1.0f, 1e-5f);
}

TEST(BuiltinCornell, AreaLightIsAQuadJustBelowTheCeilingFacingDown) {
  const Scene s = makeBuiltinScene("cornell");
  const Mesh& light = s.meshes[findMesh(s, "cornell-light")];
  EXPECT_TRUE(s.materials[light.material].isEmissive());
  EXPECT_FALSE(s.materials[light.material].doubleSided);
  EXPECT_EQ(light.triangleCount(), 2u);
  for (const glm::vec3& n : light.normals) EXPECT_EQ(n, glm::vec3(0, -1, 0));
  for (const glm::vec3& p : light.positions) {
    EXPECT_NEAR(p.y, 1.999f, 1e-6f);
    EXPECT_LT(std::abs(p.x), 1.0f);
    EXPECT_LT(std::abs(p.z), 1.0f);
  }
  EXPECT_NEAR(meshSurfaceArea(light), 0.25, 1e-6);  // a quarter of the ceiling's width, squared
  int emissive = 0;
  for (const Mesh& m : s.meshes) emissive += s.materials[m.material].isEmissive();
  EXPECT_EQ(emissive, 1);
  EXPECT_TRUE(s.lights.empty());
  EXPECT_EQ(s.environment.type, Environment::Type::None);
}

TEST(BuiltinCornell, MaterialsAreTheClassicOnes) {
  const Scene s = makeBuiltinScene("cornell");
  EXPECT_EQ(materialOfMesh(s, "cornell-left-wall").baseColorFactor,
            glm::vec4(0.65f, 0.05f, 0.05f, 1));
  EXPECT_EQ(materialOfMesh(s, "cornell-right-wall").baseColorFactor,
            glm::vec4(0.12f, 0.45f, 0.15f, 1));
  EXPECT_EQ(materialOfMesh(s, "cornell-white-walls").baseColorFactor,
            glm::vec4(0.73f, 0.73f, 0.73f, 1));
  const Material& tall = materialOfMesh(s, "cornell-tall-block");
  EXPECT_EQ(tall.metallicFactor, 1.0f);
  EXPECT_EQ(tall.roughnessFactor, 0.25f);
  const Material& low = materialOfMesh(s, "cornell-short-block");
  EXPECT_EQ(low.metallicFactor, 0.0f);
  EXPECT_EQ(low.roughnessFactor, 0.7f);
  // Angles through atan2 of float matrix entries: 1e-3 degrees is float rounding.
  EXPECT_NEAR(yRotationDegrees(instanceOf(s, "cornell-tall-block").transform), -18.0f, 1e-3f);
  EXPECT_NEAR(yRotationDegrees(instanceOf(s, "cornell-short-block").transform), 17.0f, 1e-3f);
}

// ---------------------------------------------------------------------------------------
// spheres

TEST(BuiltinSpheres, TwentyFiveSpheresSweepRoughnessAndMetallic) {
  const Scene s = makeBuiltinScene("spheres");
  std::set<std::pair<float, float>> sweep;
  int spheres = 0;
  for (const Instance& inst : s.instances) {
    const Mesh& m = s.meshes[inst.mesh];
    if (m.name.rfind("sphere-", 0) != 0) continue;
    ++spheres;
    const Material& mat = s.materials[m.material];
    sweep.insert({mat.metallicFactor, mat.roughnessFactor});
  }
  EXPECT_EQ(spheres, 25);
  std::set<std::pair<float, float>> expected;
  for (const float m : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f})
    for (const float r : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) expected.insert({m, r});
  EXPECT_EQ(sweep, expected);  // exact: quarters are exact in float
}

TEST(BuiltinSpheres, SkyAndSunAgree) {
  const Scene s = makeBuiltinScene("spheres");
  EXPECT_EQ(s.environment.type, Environment::Type::Sky);
  EXPECT_GT(s.environment.zenithColor.b, 0.0f);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, Light::Type::Directional);
  EXPECT_NEAR(glm::dot(s.lights[0].direction, -s.environment.sunDirection), 1.0f, 1e-6f);
  EXPECT_GE(s.lights[0].intensity, 3.0f);
  EXPECT_LE(s.lights[0].intensity, 10.0f);
}

// ---------------------------------------------------------------------------------------
// atrium

TEST(BuiltinAtrium, IsLargeAndInstanced) {
  const Scene s = makeBuiltinScene("atrium");
  EXPECT_GE(s.instancedTriangleCount(), 200000u);
  std::vector<int> uses(s.meshes.size(), 0);
  for (const Instance& inst : s.instances) ++uses[inst.mesh];
  EXPECT_EQ(uses[findMesh(s, "column")], 40);
  EXPECT_GE(uses[findMesh(s, "arch")], 2);
  size_t stored = 0;
  for (const Mesh& m : s.meshes) stored += m.triangleCount();
  EXPECT_LT(stored * 10, s.instancedTriangleCount());  // instancing saves > 90 %
}

TEST(BuiltinAtrium, MaterialsCoverTexturesMaskDoubleSidedAndMetal) {
  const Scene s = makeBuiltinScene("atrium");
  const Material& floor = materialOfMesh(s, "floor");
  ASSERT_TRUE(floor.baseColorTexture.valid());
  EXPECT_FALSE(floor.baseColorTexture.transform.isIdentity());
  EXPECT_NEAR(floor.roughnessFactor, 0.3f, 1e-6f);
  const Material& screen = materialOfMesh(s, "lattice-screen");
  EXPECT_EQ(screen.alphaMode, AlphaMode::Mask);
  EXPECT_EQ(screen.alphaCutoff, 0.5f);
  EXPECT_TRUE(screen.doubleSided);
  ASSERT_TRUE(screen.baseColorTexture.valid());
  std::set<uint8_t> alphas;
  const Texture& lattice = s.textures[screen.baseColorTexture.texture];
  for (size_t i = 3; i < lattice.rgba.size(); i += 4) alphas.insert(lattice.rgba[i]);
  EXPECT_EQ(alphas, (std::set<uint8_t>{0, 255}));  // holes and bars, nothing in between
  EXPECT_EQ(materialOfMesh(s, "capital").metallicFactor, 1.0f);
  EXPECT_EQ(s.textures[floor.baseColorTexture.texture].width, 256);
}

TEST(BuiltinAtrium, WarmPointLightsAlongTheNaveAndASky) {
  const Scene s = makeBuiltinScene("atrium");
  EXPECT_EQ(s.environment.type, Environment::Type::Sky);
  ASSERT_GE(s.lights.size(), 3u);
  ASSERT_LE(s.lights.size(), 4u);
  for (const Light& l : s.lights) {
    EXPECT_EQ(l.type, Light::Type::Point);
    EXPECT_GE(l.intensity, 20.0f);
    EXPECT_LE(l.intensity, 50.0f);
    EXPECT_GT(l.color.r, l.color.b);  // warm
    EXPECT_LT(std::abs(l.position.x), 5.0f);
  }
}

TEST(BuiltinAtrium, CameraAtEyeHeightInTheNaveUnderAnOpenRoof) {
  const Scene s = makeBuiltinScene("atrium");
  const Camera& c = s.cameras[0];
  EXPECT_NEAR(c.position.y, 1.7f, 1e-6f);
  EXPECT_LT(std::abs(c.position.x), 5.0f);
  const glm::vec3 forward = c.orientation * glm::vec3(0, 0, -1);
  EXPECT_LT(forward.z, -0.9f);  // along the nave
  const std::vector<Triangle> tris = worldTriangles(s);
  EXPECT_FALSE(nearestHit(tris, c.position, {0, 1, 0}).has_value());  // sky above
  EXPECT_TRUE(nearestHit(tris, c.position, forward).has_value());     // the far end wall
  EXPECT_TRUE(nearestHit(tris, c.position, {1, 0, 0}).has_value());   // walls at the side
}

}  // namespace
}  // namespace photovr
