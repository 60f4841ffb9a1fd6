#include "core/gltf_writer.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/gltf_loader.h"
#include "tests/core/test_dir.h"

namespace photovr {
namespace {

namespace fs = std::filesystem;

fs::path testDir() {
  return testing::freshTestDir("photovr_gltf_writer");
}

Mesh quad() {
  Mesh m;
  m.name = "quad";
  m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  m.normals.assign(4, glm::vec3(0, 0, 1));
  m.uv0 = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.uv1 = {{0.5f, 0}, {1, 0.25f}, {1, 1}, {0, 1}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.material = 0;
  return m;
}

Mesh triangle() {
  Mesh m;
  m.name = "tri";
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, -1}};
  m.normals.assign(3, glm::vec3(0, 1, 0));
  m.indices = {0, 1, 2};
  m.material = 1;
  return m;
}

Material texturedMaterial() {
  Material m;
  m.name = "painted";
  m.baseColorFactor = {0.9f, 0.5f, 0.25f, 0.75f};
  m.metallicFactor = 0.2f;
  m.roughnessFactor = 0.6f;
  m.emissiveFactor = {1.0f, 0.5f, 0.0f};
  m.emissiveStrength = 5.0f;
  m.normalScale = 0.5f;
  m.occlusionStrength = 0.7f;
  m.alphaMode = AlphaMode::Mask;
  m.alphaCutoff = 0.3f;
  m.doubleSided = true;
  m.baseColorTexture = {0, 1, {{0.25f, 0.5f}, 0.3f, {2.0f, 3.0f}}};
  m.metallicRoughnessTexture = {0, 0, {}};
  m.normalTexture = {0, 0, {}};
  m.occlusionTexture = {0, 0, {}};
  m.emissiveTexture = {0, 0, {}};
  m.ior = 1.33f;
  m.specularFactor = 0.5f;
  m.specularColorFactor = {1.0f, 0.5f, 2.0f};
  m.specularTexture = {0, 0, {}};
  m.specularColorTexture = {0, 1, {{0.5f, 0.0f}, 0.0f, {1.0f, 2.0f}}};
  m.transmissionFactor = 0.25f;
  m.transmissionTexture = {0, 0, {}};
  m.thicknessFactor = 0.1f;
  m.attenuationColor = {0.5f, 0.75f, 1.0f};
  m.attenuationDistance = 3.0f;
  m.sheenColorFactor = {0.5f, 0.25f, 1.0f};
  m.sheenRoughnessFactor = 0.3f;
  m.sheenColorTexture = {0, 0, {}};
  m.sheenRoughnessTexture = {0, 1, {}};
  m.clearcoatFactor = 0.75f;
  m.clearcoatRoughnessFactor = 0.125f;
  m.clearcoatTexture = {0, 0, {}};
  m.clearcoatRoughnessTexture = {0, 0, {{0.0f, 0.5f}, 0.0f, {1.0f, 1.0f}}};
  m.clearcoatNormalTexture = {0, 1, {}};
  m.clearcoatNormalScale = 0.25f;
  return m;
}

Texture checker() {
  Texture t;
  t.name = "checker";
  t.width = 3;
  t.height = 2;
  t.rgba = {255, 0,  0,  255, 0,  255, 0,  128, 0,  0,   255, 0,
            10,  20, 30, 40,  50, 60,  70, 80,  90, 100, 110, 120};
  t.wrapS = Texture::Wrap::Clamp;
  t.wrapT = Texture::Wrap::Mirror;
  t.nearest = true;
  return t;
}

Light light(Light::Type type, const glm::vec3& position, const glm::vec3& direction) {
  Light l;
  l.type = type;
  l.name = "light" + std::to_string(int(type));
  l.color = {1.0f, 0.8f, 0.6f};
  l.intensity = 42.0f + float(type);
  l.range = type == Light::Type::Point ? 10.0f : 0.0f;
  l.innerConeAngle = 0.2f;
  l.outerConeAngle = 0.6f;
  l.position = position;
  l.direction = glm::normalize(direction);
  return l;
}

Instance instance(int mesh, const glm::mat4& transform, const std::string& name) {
  Instance i;
  i.mesh = mesh;
  i.transform = transform;
  i.previousTransform = transform;
  i.node = name;
  return i;
}

Scene testScene() {
  Scene s;
  s.meshes = {quad(), triangle()};
  s.materials = {texturedMaterial(), Material{}};
  s.materials[1].name = "plain";
  s.textures = {checker()};
  const glm::mat4 parent = glm::translate(glm::mat4(1.0f), {1, 2, 3});
  const glm::mat4 child = glm::scale(glm::rotate(parent, 0.7f, glm::normalize(glm::vec3(1, 2, 3))),
                                     glm::vec3(0.5f, 2.0f, 1.0f));
  s.instances = {instance(0, parent, "parent"), instance(0, child, "child"),
                 instance(1, glm::mat4(1.0f), "tri")};
  s.lights = {light(Light::Type::Point, {1, 2, 3}, {0, 0, -1}),
              light(Light::Type::Spot, {0, 5, 0}, {0.3f, -1, 0.2f}),
              light(Light::Type::Directional, {0, 0, 0}, {0, 0, 1})};  // opposite of -Z
  Camera c;
  c.name = "eye";
  c.position = {0, 1.6f, 4};
  c.orientation = glm::angleAxis(0.4f, glm::normalize(glm::vec3(0.2f, 1, 0)));
  c.yfov = 0.9f;
  c.aspect = 1.5f;
  c.znear = 0.1f;
  c.zfar = 100.0f;
  s.cameras = {c};
  s.environment.type = Environment::Type::Constant;
  s.environment.name = "grey";
  return s;
}

// Float values survive exactly: float -> double -> JSON (round-trip digits) -> float.
// Derived quantities (transforms composed, directions from quaternions) use 1e-5, a few
// single-precision ulps of values near 1.
constexpr float kDerivedTolerance = 1e-5f;

void expectVecNear(const glm::vec3& a, const glm::vec3& b) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], kDerivedTolerance) << i;
}

void expectSameMaterial(const Material& a, const Material& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.baseColorFactor, b.baseColorFactor);
  EXPECT_EQ(a.metallicFactor, b.metallicFactor);
  EXPECT_EQ(a.roughnessFactor, b.roughnessFactor);
  EXPECT_EQ(a.emissiveFactor, b.emissiveFactor);
  EXPECT_EQ(a.emissiveStrength, b.emissiveStrength);
  EXPECT_EQ(a.normalScale, b.normalScale);
  EXPECT_EQ(a.occlusionStrength, b.occlusionStrength);
  EXPECT_EQ(a.alphaMode, b.alphaMode);
  EXPECT_EQ(a.alphaCutoff, b.alphaCutoff);
  EXPECT_EQ(a.doubleSided, b.doubleSided);
  EXPECT_EQ(a.ior, b.ior);
  EXPECT_EQ(a.specularFactor, b.specularFactor);
  EXPECT_EQ(a.specularColorFactor, b.specularColorFactor);
  EXPECT_EQ(a.transmissionFactor, b.transmissionFactor);
  EXPECT_EQ(a.thicknessFactor, b.thicknessFactor);
  EXPECT_EQ(a.attenuationColor, b.attenuationColor);
  EXPECT_EQ(a.attenuationDistance, b.attenuationDistance);
  EXPECT_EQ(a.unlit, b.unlit);
  EXPECT_EQ(a.sheenColorFactor, b.sheenColorFactor);
  EXPECT_EQ(a.sheenRoughnessFactor, b.sheenRoughnessFactor);
  EXPECT_EQ(a.clearcoatFactor, b.clearcoatFactor);
  EXPECT_EQ(a.clearcoatRoughnessFactor, b.clearcoatRoughnessFactor);
  EXPECT_EQ(a.clearcoatNormalScale, b.clearcoatNormalScale);
  const TextureRef* ra[] = {
      &a.baseColorTexture,      &a.metallicRoughnessTexture, &a.normalTexture,
      &a.occlusionTexture,      &a.emissiveTexture,          &a.specularTexture,
      &a.specularColorTexture,  &a.transmissionTexture,      &a.sheenColorTexture,
      &a.sheenRoughnessTexture, &a.clearcoatTexture,         &a.clearcoatRoughnessTexture,
      &a.clearcoatNormalTexture};
  const TextureRef* rb[] = {
      &b.baseColorTexture,      &b.metallicRoughnessTexture, &b.normalTexture,
      &b.occlusionTexture,      &b.emissiveTexture,          &b.specularTexture,
      &b.specularColorTexture,  &b.transmissionTexture,      &b.sheenColorTexture,
      &b.sheenRoughnessTexture, &b.clearcoatTexture,         &b.clearcoatRoughnessTexture,
      &b.clearcoatNormalTexture};
  for (int i = 0; i < 13; ++i) {
    EXPECT_EQ(ra[i]->texture, rb[i]->texture) << i;
    EXPECT_EQ(ra[i]->texCoord, rb[i]->texCoord) << i;
    EXPECT_EQ(ra[i]->transform.offset, rb[i]->transform.offset) << i;
    EXPECT_EQ(ra[i]->transform.rotation, rb[i]->transform.rotation) << i;
    EXPECT_EQ(ra[i]->transform.scale, rb[i]->transform.scale) << i;
  }
}

void expectSameMeshes(const Scene& in, const Scene& out) {
  ASSERT_EQ(out.meshes.size(), in.meshes.size());
  for (size_t i = 0; i < in.meshes.size(); ++i) {
    const Mesh &a = in.meshes[i], &b = out.meshes[i];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.normals, b.normals);
    EXPECT_EQ(a.uv0, b.uv0);
    EXPECT_EQ(a.uv1, b.uv1);
    EXPECT_EQ(a.indices, b.indices);
    EXPECT_EQ(a.material, b.material);
  }
  // The quad's material has a normal texture: tangents are generated on load.
  EXPECT_EQ(out.meshes[0].tangents.size(), 4u);
}

void expectSameInstances(const Scene& in, const Scene& out) {
  ASSERT_EQ(out.instances.size(), in.instances.size());
  for (size_t i = 0; i < in.instances.size(); ++i) {
    EXPECT_EQ(out.instances[i].mesh, in.instances[i].mesh);
    EXPECT_EQ(out.instances[i].node, in.instances[i].node);
    EXPECT_EQ(out.instances[i].transform, in.instances[i].transform);  // matrix stored as is
  }
}

void expectSameLights(const Scene& in, const Scene& out) {
  ASSERT_EQ(out.lights.size(), in.lights.size());
  for (size_t i = 0; i < in.lights.size(); ++i) {
    const Light &a = in.lights[i], &b = out.lights[i];
    EXPECT_EQ(a.type, b.type);
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.color, b.color);
    EXPECT_EQ(a.intensity, b.intensity);
    EXPECT_EQ(a.range, b.range);
    expectVecNear(a.position, b.position);
    expectVecNear(a.direction, b.direction);
    if (a.type == Light::Type::Spot) {
      EXPECT_EQ(a.innerConeAngle, b.innerConeAngle);
      EXPECT_EQ(a.outerConeAngle, b.outerConeAngle);
    }
  }
}

void expectSameCamera(const Camera& a, const Camera& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.yfov, b.yfov);
  EXPECT_EQ(a.aspect, b.aspect);
  EXPECT_EQ(a.znear, b.znear);
  EXPECT_EQ(a.zfar, b.zfar);
  expectVecNear(a.position, b.position);
  // q and -q are the same rotation.
  EXPECT_NEAR(std::abs(glm::dot(a.orientation, b.orientation)), 1.0f, kDerivedTolerance);
}

void expectRoundTrip(const std::string& file) {
  const Scene in = testScene();
  const std::string path = (testDir() / file).string();
  const std::vector<std::string> writeWarnings = writeGlb(in, path);
  ASSERT_EQ(writeWarnings.size(), 1u);
  EXPECT_NE(writeWarnings[0].find("environment"), std::string::npos);
  const Scene out = loadGltf(path);
  expectSameMeshes(in, out);
  expectSameInstances(in, out);
  ASSERT_EQ(out.materials.size(), 2u);
  expectSameMaterial(in.materials[0], out.materials[0]);
  expectSameMaterial(in.materials[1], out.materials[1]);
  ASSERT_EQ(out.textures.size(), 1u);
  EXPECT_EQ(out.textures[0].name, "checker");
  EXPECT_EQ(out.textures[0].width, 3);
  EXPECT_EQ(out.textures[0].height, 2);
  EXPECT_EQ(out.textures[0].rgba, in.textures[0].rgba);  // PNG is lossless
  EXPECT_EQ(out.textures[0].wrapS, Texture::Wrap::Clamp);
  EXPECT_EQ(out.textures[0].wrapT, Texture::Wrap::Mirror);
  EXPECT_TRUE(out.textures[0].nearest);
  expectSameLights(in, out);
  ASSERT_EQ(out.cameras.size(), 1u);
  expectSameCamera(in.cameras[0], out.cameras[0]);
  EXPECT_TRUE(out.warnings.empty()) << out.warnings.front();
}

TEST(GltfWriter, GlbRoundTripPreservesTheScene) {
  expectRoundTrip("scene.glb");
}

TEST(GltfWriter, GltfRoundTripPreservesTheScene) {
  expectRoundTrip("scene.gltf");
}

// An infinite camera (zfar 0) is written without zfar, as glTF 2.0 requires (§5.13: zfar > 0
// when present), in both containers; a finite one keeps it, and both read back as written.
TEST(GltfWriter, InfiniteCameraHasNoZfar) {
  Scene in = testScene();
  Camera finite = in.cameras[0];
  in.cameras[0].zfar = 0.0f;
  in.cameras[0].name = "infinite";
  in.cameras.push_back(finite);
  for (const char* file : {"infinite.gltf", "infinite.glb"}) {
    const std::string path = (testDir() / file).string();
    writeGlb(in, path);
    std::ifstream f(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(f)), {});
    size_t zfars = 0;
    for (size_t at = bytes.find("\"zfar\""); at != std::string::npos;
         at = bytes.find("\"zfar\"", at + 1))
      ++zfars;
    EXPECT_EQ(zfars, 1u) << file;  // the finite camera's alone
    const Scene out = loadGltf(path);
    ASSERT_EQ(out.cameras.size(), 2u) << file;
    expectSameCamera(in.cameras[0], out.cameras[0]);
    expectSameCamera(in.cameras[1], out.cameras[1]);
    if (std::string(file).ends_with(".glb")) {  // §4.4: lengths agree, JSON padded to 4
      uint32_t total = 0, json = 0;
      std::memcpy(&total, bytes.data() + 8, 4);
      std::memcpy(&json, bytes.data() + 12, 4);
      EXPECT_EQ(total, bytes.size());
      EXPECT_EQ(json % 4, 0u);
    }
  }
}

TEST(GltfWriter, UnlitMaterialRoundTrips) {
  Scene s = testScene();
  s.materials[1].unlit = true;
  const std::string path = (testDir() / "unlit.glb").string();
  writeGlb(s, path);
  EXPECT_TRUE(loadGltf(path).materials.at(1).unlit);
}

TEST(GltfWriter, BlendMaterialRoundTrips) {
  Scene s = testScene();
  s.materials[1].alphaMode = AlphaMode::Blend;
  const std::string path = (testDir() / "blend.glb").string();
  writeGlb(s, path);
  const Scene out = loadGltf(path);
  EXPECT_EQ(out.materials.at(1).alphaMode, AlphaMode::Blend);
  EXPECT_TRUE(out.warnings.empty());  // BLEND is rendered (stochastic coverage)
}

TEST(GltfWriter, LeavesNoTemporaryFiles) {
  const fs::path dir = testDir();
  writeGlb(testScene(), (dir / "a.glb").string());
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    ++files;
    EXPECT_EQ(entry.path().filename(), "a.glb");
  }
  EXPECT_EQ(files, 1);
}

TEST(GltfWriter, ErrorsNameThePath) {
  const std::string unwritable = "/proc/photovr_no_such_dir/x.glb";
  try {
    writeGlb(testScene(), unwritable);
    ADD_FAILURE() << "wrote to " << unwritable;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(unwritable), std::string::npos) << e.what();
  }
  EXPECT_THROW(writeGlb(testScene(), (testDir() / "scene.obj").string()), InputError);
}

}  // namespace
}  // namespace photovr
