#include "core/scene_info.h"

#include <gtest/gtest.h>

#include "core/builtin_scenes.h"
#include "core/bvh_layout.h"
#include "core/mesh_gen.h"

#include <glm/gtc/matrix_transform.hpp>

namespace photovr {
namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The smallest scene with one triangle mesh instanced once, for flag-by-flag tests.
Scene oneQuad(const Material& material) {
  Scene s;
  s.name = "quad";
  s.materials.push_back(material);
  s.meshes.push_back(makeQuad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
  s.instances.push_back(Instance{});
  return s;
}

// The BVH layout info prints is the one the tracer builds (core/bvh_layout.h): one level
// while copying the shared meshes at most doubles the stored triangles.
TEST(SceneInfo, BvhLevelsFollowWhatCopyingTheSharedMeshesWouldCost) {
  Scene s = oneQuad(Material{});
  EXPECT_TRUE(bvhLayoutOf(s).oneLevel);
  EXPECT_TRUE(contains(describeScene(s),
                       "BVH: one level (every instance's mesh in world space, "
                       "1.00x the stored triangles)"));
  s.instances.push_back(Instance{});  // the quad twice: copies hold 2x its triangles
  EXPECT_DOUBLE_EQ(bvhLayoutOf(s).copies, 2.0);
  EXPECT_TRUE(bvhLayoutOf(s).oneLevel);
  s.instances.push_back(Instance{});  // three times: above 2x
  EXPECT_FALSE(bvhLayoutOf(s).oneLevel);
  EXPECT_TRUE(contains(describeScene(s),
                       "BVH: two levels (copying the shared meshes would take "
                       "3.0x the stored triangles, above 2x)"))
      << describeScene(s);
  Scene skinned = oneQuad(Material{});
  skinned.meshes[0].skinning.skin = 0;
  EXPECT_TRUE(bvhLayoutOf(skinned).moves);
  EXPECT_FALSE(bvhLayoutOf(skinned).oneLevel);
  EXPECT_TRUE(contains(describeScene(makeBuiltinScene("atrium")), "BVH: two levels"));
  EXPECT_TRUE(contains(describeScene(makeBuiltinScene("cornell")), "BVH: one level"));
}

TEST(SceneInfo, EmptySceneNeedsNothingAndWarnsItIsBlack) {
  const SceneFeatures f = analyzeScene(Scene{});
  EXPECT_FALSE(f.punctualLights || f.areaLights || f.environment || f.alphaMask);
  EXPECT_EQ(f.emissiveTriangles, 0u);
  const std::string text = describeScene(Scene{});
  EXPECT_TRUE(contains(text, "punctual lights: none (no shadow rays)")) << text;
  EXPECT_TRUE(contains(text, "area lights: none (no area-light sampling)")) << text;
  EXPECT_TRUE(contains(text, "environment: none (misses are black)")) << text;
  EXPECT_TRUE(contains(text, "alpha mask: no")) << text;
  EXPECT_TRUE(contains(text, "the image will be black")) << text;
  EXPECT_TRUE(contains(text, "world bounds: empty")) << text;
}

// Issue 23: a scene 1e7 m from the origin is snapped to a 1 m float grid; info and render
// say so. At 1 km the spacing (6e-5 m) is 1/57000 of cornell's 3.5 m extent: no warning.
TEST(SceneInfo, GeometryFarFromTheOriginIsAWarningNamingThePrecision) {
  auto moved = [](float offset) {
    Scene s = makeBuiltinScene("cornell");
    for (Instance& i : s.instances)
      i.transform = glm::translate(glm::mat4(1.0f), glm::vec3(offset, 0, 0)) * i.transform;
    return s;
  };
  auto farWarning = [](const Scene& s) {
    for (const std::string& w : analyzeScene(s).warnings)
      if (contains(w, "from the origin")) return w;
    return std::string();
  };
  EXPECT_EQ(farWarning(moved(0.0f)), "");
  EXPECT_EQ(farWarning(moved(1e3f)), "");
  const std::string w = farWarning(moved(1e7f));
  EXPECT_TRUE(contains(w, "up to 1e+07 m from the origin, where floats are 1 m apart")) << w;
}

// Vertex data stored far from its mesh's own origin lost its precision in the file: no
// re-basing recovers it, so info says which mesh and how much.
TEST(SceneInfo, FarVertexDataIsAWarningNamingTheMesh) {
  Scene s = makeBuiltinScene("cornell");
  EXPECT_EQ(describeScene(s).find("stores vertices"), std::string::npos);
  for (glm::vec3& p : s.meshes[0].positions) p += glm::vec3(1e7f, 0.0f, 0.0f);
  std::string found;
  for (const std::string& w : analyzeScene(s).warnings)
    if (contains(w, "stores vertices")) found = w;
  EXPECT_TRUE(contains(found, "mesh '" + s.meshes[0].name +
                                  "' stores vertices up to 1e+07 m from its own origin, "
                                  "where floats are 1 m apart"))
      << found;
}

TEST(SceneInfo, UnlitSurfacesAreSomethingThatShows) {
  Material m;
  m.unlit = true;
  const SceneFeatures f = analyzeScene(oneQuad(m));
  for (const std::string& w : f.warnings) EXPECT_FALSE(contains(w, "no light")) << w;
}

TEST(SceneInfo, EmissiveMaterialCountsInstancedTriangles) {
  Material m;
  m.emissiveFactor = glm::vec3(1.0f);
  Scene s = oneQuad(m);
  s.instances.push_back(Instance{});  // the same quad twice: 4 world triangles
  const SceneFeatures f = analyzeScene(s);
  EXPECT_TRUE(f.areaLights);
  EXPECT_EQ(f.emissiveTriangles, 4u);
  EXPECT_TRUE(contains(describeScene(s), "area lights: 4 emissive triangles"));
}

TEST(SceneInfo, ZeroStrengthEmissionIsNotALight) {
  Material m;
  m.emissiveFactor = glm::vec3(1.0f);
  m.emissiveStrength = 0.0f;
  EXPECT_FALSE(analyzeScene(oneQuad(m)).areaLights);
}

TEST(SceneInfo, MaskOnlyCountsWhenInstanced) {
  Material mask;
  mask.alphaMode = AlphaMode::Mask;
  Scene s = oneQuad(Material{});
  s.materials.push_back(mask);  // present but used by no mesh
  EXPECT_FALSE(analyzeScene(s).alphaMask);
  s.meshes[0].material = 1;
  EXPECT_TRUE(analyzeScene(s).alphaMask);
}

TEST(SceneInfo, WarnsAboutBrokenInstancesAndUnusedMeshes) {
  Scene s = oneQuad(Material{});
  s.meshes.push_back(s.meshes[0]);
  Instance broken;
  broken.mesh = 7;
  s.instances.push_back(broken);
  const SceneFeatures f = analyzeScene(s);
  ASSERT_GE(f.warnings.size(), 2u);
  EXPECT_TRUE(contains(f.warnings[0], "1 instances name a mesh that does not exist"));
  EXPECT_TRUE(contains(f.warnings[1], "1 meshes are used by no instance"));
  EXPECT_NO_THROW(describeScene(s));  // a broken scene is described, not crashed on
}

TEST(SceneInfo, MapEnvironmentShowsItsSize) {
  Scene s;
  s.environment.type = Environment::Type::Map;
  s.environment.width = 8;
  s.environment.height = 4;
  s.environment.pixels.assign(32, glm::vec3(1.0f));
  EXPECT_TRUE(analyzeScene(s).environment);
  EXPECT_TRUE(contains(describeScene(s), "environment: map 8x4"));
}

TEST(SceneInfo, CornellNeedsAreaLightsOnly) {
  const Scene s = makeBuiltinScene("cornell");
  const SceneFeatures f = analyzeScene(s);
  EXPECT_FALSE(f.punctualLights);
  EXPECT_TRUE(f.areaLights);
  EXPECT_EQ(f.emissiveTriangles, 2u);
  EXPECT_FALSE(f.environment);
  EXPECT_FALSE(f.alphaMask);
  EXPECT_TRUE(f.warnings.empty());
  const std::string text = describeScene(s);
  EXPECT_TRUE(contains(text, "punctual lights: none (no shadow rays)")) << text;
  EXPECT_TRUE(contains(text, "area lights: 2 emissive triangles")) << text;
  EXPECT_TRUE(contains(text, "environment: none (misses are black)")) << text;
  EXPECT_TRUE(contains(text, "alpha mask: no")) << text;
  EXPECT_TRUE(contains(text, "cornell-view at (0.00, 1.00, 0.90), yfov 55.0 deg")) << text;
  EXPECT_TRUE(contains(text, "warnings: none")) << text;
}

TEST(SceneInfo, SpheresNeedTheSunAndTheSky) {
  const Scene s = makeBuiltinScene("spheres");
  const SceneFeatures f = analyzeScene(s);
  EXPECT_TRUE(f.punctualLights);
  EXPECT_EQ(f.directionalLights, 1u);
  EXPECT_FALSE(f.areaLights);
  EXPECT_TRUE(f.environment);
  const std::string text = describeScene(s);
  EXPECT_TRUE(contains(text, "instances: 26 (")) << text;
  EXPECT_TRUE(contains(text, "punctual lights: 1 (shadow rays)")) << text;
  EXPECT_TRUE(contains(text, "area lights: none")) << text;
  EXPECT_TRUE(contains(text, "  environment: sky")) << text;
  EXPECT_TRUE(contains(text, "metal 5, dielectric 6, partly metallic 15")) << text;
}

TEST(SceneInfo, AtriumNeedsLightsSkyAndAlphaMask) {
  const Scene s = makeBuiltinScene("atrium");
  const SceneFeatures f = analyzeScene(s);
  EXPECT_TRUE(f.punctualLights);
  EXPECT_EQ(f.pointLights, s.lights.size());
  EXPECT_TRUE(f.environment);
  EXPECT_TRUE(f.alphaMask);
  EXPECT_TRUE(f.doubleSided);
  const std::string text = describeScene(s);
  EXPECT_TRUE(contains(text, "punctual lights: 4 (shadow rays)")) << text;
  EXPECT_TRUE(contains(text, "alpha mask: yes (any-hit filter)")) << text;
  // Only the lattice screens (MASK) need the any-hit filter; the single-sided rest are
  // culled for camera rays alone (trace/embree_scene.h, RayRole).
  EXPECT_EQ(f.filteredMeshes, 1u);
  EXPECT_TRUE(f.singleSided);
  EXPECT_TRUE(contains(text, "single-sided back faces: culled for camera rays")) << text;
  EXPECT_TRUE(contains(text, "generated-marble-checker 256x256")) << text;
  // Counts are printed with thousands separators; rebuild the instanced one to compare.
  std::string n = std::to_string(s.instancedTriangleCount());
  for (int i = int(n.size()) - 3; i > 0; i -= 3) n.insert(size_t(i), ",");
  EXPECT_TRUE(contains(text, n + " triangles instanced")) << text;
}

}  // namespace
}  // namespace photovr
