#include "core/gltf_loader.h"

#include <gtest/gtest.h>

#include "tests/core/test_dir.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "core/gltf_writer.h"
#include "core/image_io.h"
#include "core/scene_info.h"

namespace photovr {
namespace {

namespace fs = std::filesystem;

fs::path testDir() {
  return testing::freshTestDir("photovr_gltf_loader");
}

void writeFile(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string base64(const std::string& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 2]));
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[v & 63] : '=';
  }
  return out;
}

template <typename T>
void append(std::string& bytes, std::initializer_list<T> values) {
  for (T v : values) bytes.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

std::string dataUri(const std::string& bytes) {
  return "data:application/octet-stream;base64," + base64(bytes);
}

// Triangle (0,0,0) (1,0,0) (0,1,0): 36 bytes of float positions, then 3 u16 indices.
std::string triangleBuffer(float x0 = 0.0f) {
  std::string b;
  append<float>(b, {x0, 0, 0, 1, 0, 0, 0, 1, 0});
  append<uint16_t>(b, {0, 1, 2});
  return b;
}

// A minimal valid glTF; tests break one piece of it with replace().
std::string triangleGltf(const std::string& buffer = triangleBuffer()) {
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
"nodes":[{"mesh":0,"name":"tri"}],
"meshes":[{"name":"tri","primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
"buffers":[{"byteLength":)" +
         std::to_string(buffer.size()) + R"(,"uri":")" + dataUri(buffer) + R"("}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},
               {"buffer":0,"byteOffset":36,"byteLength":6}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",
              "min":[0,0,0],"max":[1,1,0]},
             {"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]})";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test setup: '" << from << "' not in the glTF";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::string writeGltf(const std::string& name, const std::string& json) {
  const fs::path path = testDir() / name;
  writeFile(path, json);
  return path.string();
}

// Loads a file that must fail; checks the error policy: one line, naming the file.
std::string loadError(const std::string& path) {
  try {
    loadGltf(path);
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_NE(what.find(fs::path(path).filename().string()), std::string::npos) << what;
    return what;
  }
  ADD_FAILURE() << path << " loaded without an error";
  return "";
}

bool anyContains(const std::vector<std::string>& lines, const std::string& a,
                 const std::string& b = "") {
  for (const std::string& line : lines)
    if (line.find(a) != std::string::npos && line.find(b) != std::string::npos) return true;
  return false;
}

void expectMatNear(const glm::mat4& a, const glm::mat4& b, float tolerance) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], tolerance) << c << "," << r;
}

// Bytes that are neither glTF JSON nor a binary glTF: the parser's message quotes what it
// last read, and the line must not carry the file's raw bytes to the terminal.
TEST(GltfLoader, AFileOfRandomBytesIsRefusedInPrintableText) {
  std::string bytes;
  for (int i = 0; i < 256; ++i) bytes += char(255 - i);  // 0xff first: every byte value
  const std::string what = loadError(writeGltf("random.glb", bytes));
  for (char c : what) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << what;
  EXPECT_NE(what.find("\\xff"), std::string::npos) << what;
}

TEST(GltfLoader, MinimalTriangleLoadsExactPositions) {
  const Scene scene = loadGltf(writeGltf("tri.gltf", triangleGltf()));
  ASSERT_EQ(scene.meshes.size(), 1u);
  const Mesh& mesh = scene.meshes[0];
  // Flat shading (no NORMAL) un-shares vertices, but a single triangle keeps its order.
  ASSERT_EQ(mesh.positions.size(), 3u);
  EXPECT_EQ(mesh.positions[0], glm::vec3(0, 0, 0));  // exact: float32 copied, no arithmetic
  EXPECT_EQ(mesh.positions[1], glm::vec3(1, 0, 0));
  EXPECT_EQ(mesh.positions[2], glm::vec3(0, 1, 0));
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
  for (const glm::vec3& n : mesh.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_EQ(scene.instances[0].transform, glm::mat4(1.0f));
  EXPECT_EQ(scene.instances[0].node, "tri");
  // No material: the glTF default material (§3.9.6).
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materials[mesh.material].baseColorFactor, glm::vec4(1.0f));
  EXPECT_EQ(scene.materials[mesh.material].metallicFactor, 1.0f);
  EXPECT_EQ(scene.materials[mesh.material].roughnessFactor, 1.0f);
  EXPECT_TRUE(scene.warnings.empty());
}

TEST(GltfLoader, HierarchyIsFlattenedAndMeshesShared) {
  const std::string nodes =
      R"("nodes":[{"name":"parent","translation":[1,2,3],"children":[1,2]},
{"name":"a","mesh":0,"scale":[2,2,2]},
{"name":"b","mesh":0,"rotation":[0,0.7071067811865476,0,0.7071067811865476],
 "children":[3]},
{"name":"c","mesh":0,"matrix":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,5,1]}],
"scenes":[{"nodes":[0]}],)";
  const std::string json = replaced(triangleGltf(), R"("scenes":[{"nodes":[0]}],
"nodes":[{"mesh":0,"name":"tri"}],)",
                                    nodes);
  const Scene scene = loadGltf(writeGltf("tree.gltf", json));
  ASSERT_EQ(scene.meshes.size(), 1u);
  ASSERT_EQ(scene.instances.size(), 3u);
  const glm::mat4 parent = glm::translate(glm::mat4(1.0f), glm::vec3(1, 2, 3));
  const glm::mat4 rotY = glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(0, 1, 0));
  // 1e-6: products of a few single-precision matrices with entries near 1.
  expectMatNear(scene.instances[0].transform, glm::scale(parent, glm::vec3(2.0f)), 1e-6f);
  expectMatNear(scene.instances[1].transform, parent * rotY, 1e-6f);
  expectMatNear(scene.instances[2].transform,
                parent * rotY * glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 5)), 1e-6f);
  for (const Instance& instance : scene.instances) EXPECT_EQ(instance.mesh, 0);
  EXPECT_EQ(scene.instances[2].node, "c");
}

TEST(GltfLoader, InterleavedNormalizedTexcoordsAndByteIndices) {
  // Per vertex: float3 position, u8 x2 normalised uv, 2 bytes padding: stride 16.
  std::string b;
  const uint8_t uv[3][2] = {{0, 0}, {255, 0}, {0, 51}};
  const float pos[3][3] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
  for (int v = 0; v < 3; ++v) {
    append<float>(b, {pos[v][0], pos[v][1], pos[v][2]});
    append<uint8_t>(b, {uv[v][0], uv[v][1], 0, 0});
  }
  append<uint8_t>(b, {2, 1, 0, 0});  // indices, u8, reversed order; one padding byte
  std::string json = triangleGltf(b);
  json = replaced(json, R"({"buffer":0,"byteOffset":0,"byteLength":36},
               {"buffer":0,"byteOffset":36,"byteLength":6})",
                  R"({"buffer":0,"byteOffset":0,"byteLength":48,"byteStride":16},
               {"buffer":0,"byteOffset":48,"byteLength":3})");
  json = replaced(json, R"("max":[1,1,0]},)",
                  R"("max":[2,2,0]},
{"bufferView":0,"byteOffset":12,"componentType":5121,"normalized":true,"count":3,"type":"VEC2"},)");
  json = replaced(json, R"({"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"})",
                  R"({"bufferView":1,"componentType":5121,"count":3,"type":"SCALAR"})");
  json = replaced(json, R"("indices":1)", R"("indices":2)");
  json = replaced(json, R"({"POSITION":0})", R"({"POSITION":0,"TEXCOORD_0":1})");
  const Scene scene = loadGltf(writeGltf("interleaved.gltf", json));
  const Mesh& mesh = scene.meshes.at(0);
  // Flat shading un-shares in index order 2, 1, 0.
  ASSERT_EQ(mesh.positions.size(), 3u);
  EXPECT_EQ(mesh.positions[0], glm::vec3(0, 2, 0));
  EXPECT_EQ(mesh.positions[2], glm::vec3(0, 0, 0));
  ASSERT_EQ(mesh.uv0.size(), 3u);
  EXPECT_EQ(mesh.uv0[0], glm::vec2(0.0f, 51.0f / 255.0f));  // §3.11: c / 255
  EXPECT_EQ(mesh.uv0[1], glm::vec2(1.0f, 0.0f));
  for (const glm::vec3& n : mesh.normals) EXPECT_EQ(n, glm::vec3(0, 0, -1));  // reversed winding
}

TEST(GltfLoader, StripsAndFansBecomeLists) {
  std::string b;
  append<float>(b, {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
  append<uint16_t>(b, {0, 1, 2});  // unused but keeps the default layout valid
  std::string strip =
      replaced(triangleGltf(b), R"("count":3,"type":"VEC3")", R"("count":4,"type":"VEC3")");
  strip = replaced(strip, R"("byteOffset":0,"byteLength":36)", R"("byteOffset":0,"byteLength":48)");
  strip = replaced(strip, R"("byteOffset":36,"byteLength":6)", R"("byteOffset":48,"byteLength":6)");
  const std::string fan = replaced(strip, R"("indices":1)", R"("mode":6)");
  strip = replaced(strip, R"("indices":1)", R"("mode":5)");
  // §3.7.2.1: strip triangle i is (i, i+1+i%2, i+2-i%2); fan triangle i is (i+1, i+2, 0).
  const Mesh s = loadGltf(writeGltf("strip.gltf", strip)).meshes.at(0);
  ASSERT_EQ(s.positions.size(), 6u);
  EXPECT_EQ(s.positions[3], glm::vec3(1, 0, 0));
  EXPECT_EQ(s.positions[4], glm::vec3(1, 1, 0));
  EXPECT_EQ(s.positions[5], glm::vec3(0, 1, 0));
  for (const glm::vec3& n : s.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));  // consistent winding
  const Mesh f = loadGltf(writeGltf("fan.gltf", fan)).meshes.at(0);
  ASSERT_EQ(f.positions.size(), 6u);
  EXPECT_EQ(f.positions[0], glm::vec3(1, 0, 0));
  EXPECT_EQ(f.positions[2], glm::vec3(0, 0, 0));
}

TEST(GltfLoader, PointsAreSkippedWithAWarning) {
  const std::string json = replaced(triangleGltf(), R"({"attributes":{"POSITION":0},"indices":1})",
                                    R"({"attributes":{"POSITION":0},"mode":0},
                                       {"attributes":{"POSITION":0},"indices":1})");
  const Scene scene = loadGltf(writeGltf("points.gltf", json));
  EXPECT_EQ(scene.meshes.size(), 1u);
  EXPECT_TRUE(anyContains(scene.warnings, "points.gltf", "skipped"));
  const std::string onlyPoints =
      replaced(triangleGltf(), R"("indices":1)", R"("indices":1,"mode":0)");
  EXPECT_NE(loadError(writeGltf("onlypoints.gltf", onlyPoints)).find("no triangle meshes"),
            std::string::npos);
}

TEST(GltfLoader, ExternalTextureLoads) {
  const fs::path dir = testDir();
  // Opaque texels: image_io's PNG writer treats alpha as premultiplied, so a translucent
  // texel would not be stored as given (straight alpha is covered by the writer round trip).
  Image8 image(2, 1, 4);
  const uint8_t pixels[8] = {10, 20, 30, 255, 200, 100, 50, 255};
  std::memcpy(image.data.data(), pixels, 8);
  writeImage((dir / "tex.png").string(), image);
  const std::string materials = R"("materials":[
{"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.25,1,1],"baseColorTexture":{"index":0}}}],
"textures":[{"source":0,"sampler":0}],
"images":[{"uri":"tex.png"}],
"samplers":[{"magFilter":9728,"wrapS":33071,"wrapT":33648}],
"buffers":)";
  std::string json = replaced(triangleGltf(), R"("buffers":)", materials);
  json = replaced(json, R"("indices":1)", R"("indices":1,"material":0)");
  writeFile(dir / "textured.gltf", json);
  const Scene scene = loadGltf((dir / "textured.gltf").string());
  ASSERT_EQ(scene.textures.size(), 1u);
  const Texture& t = scene.textures[0];
  EXPECT_EQ(t.width, 2);
  EXPECT_EQ(t.height, 1);
  EXPECT_EQ(t.rgba, std::vector<uint8_t>(pixels, pixels + 8));
  EXPECT_TRUE(t.nearest);
  EXPECT_EQ(t.wrapS, Texture::Wrap::Clamp);
  EXPECT_EQ(t.wrapT, Texture::Wrap::Mirror);
  const Material& m = scene.materials.at(0);
  EXPECT_EQ(m.baseColorTexture.texture, 0);
  EXPECT_FALSE(m.emissiveTexture.valid());
  EXPECT_EQ(m.baseColorFactor, glm::vec4(0.5f, 0.25f, 1.0f, 1.0f));
}

// A missing or undecodable texture is bad input: an error naming the glTF file and the
// texture, as for any other broken part of the file.
TEST(GltfLoader, MissingTextureIsAnErrorNamingIt) {
  const std::string materials = R"("materials":[{"emissiveTexture":{"index":0}}],
"textures":[{"source":0}],"images":[{"uri":"nothere.png"}],"buffers":)";
  std::string json = replaced(triangleGltf(), R"("buffers":)", materials);
  json = replaced(json, R"("indices":1)", R"("indices":1,"material":0)");
  const std::string error = loadError(writeGltf("missing_texture.gltf", json));
  EXPECT_NE(error.find("missing_texture.gltf: texture 'nothere.png': file not found"),
            std::string::npos)
      << error;
}

TEST(GltfLoader, CorruptEmbeddedTextureIsAnError) {
  const std::string materials =
      R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],
"textures":[{"source":0,"name":"broken"}],
"images":[{"uri":"data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAAB"}],
"buffers":)";
  std::string json = replaced(triangleGltf(), R"("buffers":)", materials);
  json = replaced(json, R"("indices":1)", R"("indices":1,"material":0)");
  const std::string path = writeGltf("corrupt_texture.gltf", json);
  ::testing::internal::CaptureStderr();
  const std::string error = loadError(path);
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(error.find("corrupt_texture.gltf: texture 'broken': corrupt PNG image: "),
            std::string::npos)
      << error;
  // The error is ours alone: no decoder prints its own line (libpng's default handler did).
  EXPECT_EQ(printed, "");
}

// A PNG whose header claims 20000x20000 is refused before 1.6 GB are allocated for it.
TEST(GltfLoader, TextureClaimingAHugeSizeIsRefusedUnallocated) {
  // Signature, IHDR (13 bytes: width, height, depth 8, RGBA, no interlace) and its CRC.
  const std::string png =
      "iVBORw0KGgoAAAANSUhEUgAATiAAAE4gCAYAAADjcEY5AAAAC0lEQVR4nGNgAAIAAAUAAXpeqz8AAAAASUVORK5CYII"
      "=";
  const std::string materials =
      R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],
"textures":[{"source":0,"name":"huge"}],"images":[{"uri":"data:image/png;base64,)" +
      png + R"("}],"buffers":)";
  std::string json = replaced(triangleGltf(), R"("buffers":)", materials);
  json = replaced(json, R"("indices":1)", R"("indices":1,"material":0)");
  const std::string error = loadError(writeGltf("huge_texture.gltf", json));
  // stb_image's header check refuses it (above 2^30 bytes decoded); ours (2^28 pixels)
  // stands behind it for what stb lets through.
  EXPECT_NE(error.find("texture 'huge': corrupt PNG image: too large"), std::string::npos) << error;
}

// tinygltf's JSON parser recurses per level: 20 000 levels crashed it. Refused up front.
TEST(GltfLoader, DeeplyNestedJsonIsAnErrorNotACrash) {
  const std::string deep = std::string(20000, '[') + std::string(20000, ']');
  const std::string json = replaced(triangleGltf(), R"("scene":0,)", R"("extras":)" + deep + ",");
  const std::string error = loadError(writeGltf("deep.gltf", json));
  EXPECT_NE(error.find("deep.gltf: JSON nested more than 512 levels deep"), std::string::npos)
      << error;
  // Brackets inside strings are text, not nesting.
  const std::string text = "\"" + std::string(600, '[') + "\\\"\"";
  EXPECT_NO_THROW(loadGltf(writeGltf(
      "text.gltf", replaced(triangleGltf(), R"("scene":0,)", R"("extras":)" + text + ","))));
}

// A buffer URI naming a folder made tinygltf allocate without bound (std::bad_alloc).
TEST(GltfLoader, BufferThatIsNotARegularFileIsAnError) {
  std::string json = triangleGltf();
  const size_t uri = json.find(R"("uri":")");
  ASSERT_NE(uri, std::string::npos);
  json.replace(uri, json.find('"', uri + 7) + 1 - uri, R"("uri":"adir")");
  const std::string path = writeGltf("dir_buffer.gltf", json);
  fs::create_directories(fs::path(path).parent_path() / "adir");  // after: testDir() wipes
  const std::string error = loadError(path);
  EXPECT_NE(error.find("dir_buffer.gltf: cannot read "), std::string::npos) << error;
  EXPECT_NE(error.find("not a regular file"), std::string::npos) << error;
}

// Each matrix is finite; the vertices it places are not.
TEST(GltfLoader, TransformsBeyondFloatRangeAreAnError) {
  const std::string matrix = R"("matrix":[3e38,0,0,0,0,3e38,0,0,0,0,3e38,0,3e38,3e38,3e38,1],)";
  const std::string json =
      replaced(triangleGltf(), R"("mesh":0,"name":"tri")", matrix + R"("mesh":0,"name":"tri")");
  const std::string error = loadError(writeGltf("huge.gltf", json));
  EXPECT_NE(error.find("huge.gltf: the node transforms take the geometry beyond float range"),
            std::string::npos)
      << error;
}

TEST(GltfLoader, RequiredUnsupportedExtensionIsAnError) {
  const std::string json =
      replaced(triangleGltf(), R"("scene":0,)",
               R"("extensionsUsed":["KHR_texture_basisu","KHR_lights_punctual"],
"extensionsRequired":["KHR_texture_basisu"],"scene":0,)");
  const std::string error = loadError(writeGltf("basisu_required.gltf", json));
  EXPECT_NE(error.find("requires unsupported extension(s) KHR_texture_basisu"), std::string::npos);
}

// Issue 23: a file's accessors may name buffer views that only a required extension makes
// valid, which tinygltf refused first ("accessor[0] invalid bufferView", for a Draco file
// before photovr read Draco). The required extension is checked on the JSON before
// anything else, so it is the one error.
TEST(GltfLoader, RequiredExtensionIsTheFirstErrorBeforeWhatItEncodes) {
  std::string json = replaced(triangleGltf(), R"("scene":0,)",
                              R"("extensionsUsed":["KHR_texture_basisu"],
"extensionsRequired":["KHR_texture_basisu"],"scene":0,)");
  json = replaced(json, R"("bufferView":0,"componentType":5126)",
                  R"("bufferView":7,"componentType":5126)");
  const std::string error = loadError(writeGltf("basisu_views.gltf", json));
  EXPECT_NE(error.find("basisu_views.gltf: requires unsupported extension(s) "
                       "KHR_texture_basisu"),
            std::string::npos)
      << error;
  EXPECT_EQ(error.find("bufferView"), std::string::npos) << error;
}

TEST(GltfLoader, BasisTexturesSayThereIsNoDebianDecoder) {
  const std::string json = replaced(triangleGltf(), R"("scene":0,)",
                                    R"("extensionsRequired":["KHR_texture_basisu"],"scene":0,)");
  const std::string error = loadError(writeGltf("basisu.gltf", json));
  EXPECT_NE(error.find("KHR_texture_basisu (Basis Universal textures: Debian 12 ships no Basis "
                       "decoder)"),
            std::string::npos)
      << error;
}

// Issue 23: a skinned, animated model rendered in its bind pose without a word.
// Node animations play (tests/core/animation_test.cpp); what does not is named.
TEST(GltfLoader, WeightAnimationsAndMorphTargetsNotPlayedAreWarnings) {
  std::string json = replaced(triangleGltf(), R"("nodes":[{"mesh":0,"name":"tri"}],)",
                              R"("nodes":[{"mesh":0,"name":"tri"}],
"animations":[{"channels":[{"sampler":0,"target":{"node":0,"path":"weights"}}],
  "samplers":[{"input":0,"output":0}]}],
"skins":[{"joints":[0]}],)");
  json = replaced(json, R"("attributes":{"POSITION":0},"indices":1)",
                  R"("attributes":{"POSITION":0},"indices":1,"targets":[{"POSITION":0}])");
  const Scene scene = loadGltf(writeGltf("animated.gltf", json));
  EXPECT_TRUE(anyContains(scene.warnings, "animated.gltf",
                          "1 animation channel(s) of morph target weights not played"));
  // Skins are applied (core/skinning.h); one that no node uses is simply unused.
  for (const std::string& w : scene.warnings) EXPECT_EQ(w.find("skin"), std::string::npos) << w;
  EXPECT_TRUE(anyContains(scene.warnings, "animated.gltf", "1 primitive(s) with morph targets"));
}

TEST(GltfLoader, UsedUnsupportedExtensionIsAWarning) {
  const std::string json =
      replaced(triangleGltf(), R"("scene":0,)",
               R"("extensionsUsed":["EXT_foo","KHR_texture_transform","EXT_bar"],"scene":0,)");
  const Scene scene = loadGltf(writeGltf("used.gltf", json));
  EXPECT_TRUE(
      anyContains(scene.warnings, "used.gltf", "unsupported extension(s) EXT_foo, EXT_bar"));
}

TEST(GltfLoader, LightsCamerasAndTexCoordOverrideFromNodes) {
  const std::string extras = R"("nodes":[{"mesh":0,"name":"tri"},
{"name":"lamp","translation":[1,2,3],"rotation":[0.7071067811865476,0,0,0.7071067811865476],
 "extensions":{"KHR_lights_punctual":{"light":0}}},
{"name":"ortho","camera":0}],
"scenes":[{"nodes":[0,1,2]}],
"extensions":{"KHR_lights_punctual":{"lights":[{"type":"spot","color":[1,0.5,0.25],
 "intensity":7,"spot":{"innerConeAngle":0.1,"outerConeAngle":0.5}}]}},
"cameras":[{"type":"orthographic","orthographic":{"xmag":1,"ymag":1,"znear":0.1,"zfar":10}}],
"materials":[{"emissiveTexture":{"index":0,"texCoord":0,
 "extensions":{"KHR_texture_transform":{"texCoord":1,"rotation":0.5}}}}],
"textures":[{}],
"meshes":)";
  std::string json = replaced(triangleGltf(), R"("scenes":[{"nodes":[0]}],
"nodes":[{"mesh":0,"name":"tri"}],
"meshes":)",
                              extras);
  json = replaced(json, R"("indices":1)", R"("indices":1,"material":0)");
  const Scene scene = loadGltf(writeGltf("lights.gltf", json));
  ASSERT_EQ(scene.lights.size(), 1u);
  const Light& light = scene.lights[0];
  EXPECT_EQ(light.type, Light::Type::Spot);
  EXPECT_EQ(light.color, glm::vec3(1.0f, 0.5f, 0.25f));
  EXPECT_EQ(light.intensity, 7.0f);
  EXPECT_EQ(light.innerConeAngle, 0.1f);
  EXPECT_EQ(light.outerConeAngle, 0.5f);
  EXPECT_EQ(light.position, glm::vec3(1, 2, 3));
  // +90 degrees about X turns the light's -Z onto +Y; 1e-6 for the single-precision rotation.
  EXPECT_NEAR(light.direction.x, 0.0f, 1e-6f);
  EXPECT_NEAR(light.direction.y, 1.0f, 1e-6f);
  EXPECT_NEAR(light.direction.z, 0.0f, 1e-6f);
  EXPECT_TRUE(scene.cameras.empty());
  EXPECT_TRUE(anyContains(scene.warnings, "perspective", "skipped"));
  // The texture has no image source (legal glTF), so the reference is dropped; the factor
  // stays.
  EXPECT_FALSE(scene.materials.at(0).emissiveTexture.valid());
  EXPECT_TRUE(anyContains(scene.warnings, "texture#0", "no image source"));
}

TEST(GltfLoader, TexCoordOverrideAndTransformAreRead) {
  const fs::path dir = testDir();
  Image8 image(1, 1, 4);
  image.data = {1, 2, 3, 255};
  writeImage((dir / "one.png").string(), image);
  const std::string materials = R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":
{"index":0,"extensions":{"KHR_texture_transform":{"texCoord":1,"rotation":0.5,
 "offset":[0.25,0.75],"scale":[2,4]}}}}}],
"textures":[{"source":0}],"images":[{"uri":"one.png"}],
"buffers":)";
  std::string json = replaced(triangleGltf(), R"("buffers":)", materials);
  json = replaced(json, R"("indices":1)", R"("indices":1,"material":0)");
  writeFile(dir / "override.gltf", json);
  const TextureRef ref =
      loadGltf((dir / "override.gltf").string()).materials.at(0).baseColorTexture;
  EXPECT_EQ(ref.texture, 0);
  EXPECT_EQ(ref.texCoord, 1);  // the extension's texCoord overrides the textureInfo's
  EXPECT_EQ(ref.transform.rotation, 0.5f);
  EXPECT_EQ(ref.transform.offset, glm::vec2(0.25f, 0.75f));
  EXPECT_EQ(ref.transform.scale, glm::vec2(2.0f, 4.0f));
}

// ---- Malformed input: each case is one clear line, never a crash ----

TEST(GltfLoaderErrors, MissingFile) {
  EXPECT_NE(loadError((testDir() / "absent.gltf").string()).find("not found"), std::string::npos);
}

TEST(GltfLoaderErrors, EmptyFile) {
  EXPECT_NE(loadError(writeGltf("empty.gltf", "")).find("empty"), std::string::npos);
}

TEST(GltfLoaderErrors, BadJson) {
  const std::string error = loadError(writeGltf("bad.gltf", "{\"asset\": {\"version\": "));
  EXPECT_NE(error.find("JSON"), std::string::npos) << error;
}

TEST(GltfLoaderErrors, TruncatedGlb) {
  const fs::path dir = testDir();
  Scene scene = loadGltf(writeGltf("tri.gltf", triangleGltf()));
  writeGlb(scene, (dir / "full.glb").string());
  std::ifstream in(dir / "full.glb", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (size_t keep : {size_t(10), bytes.size() / 2, bytes.size() - 4}) {
    writeFile(dir / "cut.glb", bytes.substr(0, keep));
    const std::string error = loadError((dir / "cut.glb").string());
    EXPECT_NE(error.find("truncated"), std::string::npos) << keep << ": " << error;
  }
}

TEST(GltfLoaderErrors, MissingExternalBuffer) {
  const std::string json = replaced(triangleGltf(), dataUri(triangleBuffer()), "missing.bin");
  const std::string error = loadError(writeGltf("nobin.gltf", json));
  EXPECT_NE(error.find("buffer file not found: missing.bin"), std::string::npos) << error;
}

TEST(GltfLoaderErrors, ExternalBufferShorterThanDeclared) {
  const fs::path dir = testDir();
  writeFile(dir / "short.bin", triangleBuffer().substr(0, 20));
  writeFile(dir / "short.gltf", replaced(triangleGltf(), dataUri(triangleBuffer()), "short.bin"));
  const std::string error = loadError((dir / "short.gltf").string());
  EXPECT_NE(error.find("size mismatch"), std::string::npos) << error;
}

TEST(GltfLoaderErrors, DataUriShorterThanDeclared) {
  const std::string json = replaced(triangleGltf(), R"("byteLength":42,)", R"("byteLength":420,)");
  const std::string error = loadError(writeGltf("shortdata.gltf", json));
  EXPECT_NE(error.find("shorter than its byteLength"), std::string::npos) << error;
}

TEST(GltfLoaderErrors, BufferViewOutOfRange) {
  const std::string json = replaced(triangleGltf(), R"("byteOffset":36,"byteLength":6)",
                                    R"("byteOffset":36,"byteLength":60)");
  EXPECT_NE(loadError(writeGltf("view.gltf", json)).find("out of range"), std::string::npos);
}

TEST(GltfLoaderErrors, AccessorOutOfRange) {
  const std::string json =
      replaced(triangleGltf(), R"("count":3,"type":"VEC3")", R"("count":30,"type":"VEC3")");
  const std::string error = loadError(writeGltf("accessor.gltf", json));
  EXPECT_NE(error.find("out of range"), std::string::npos) << error;
}

TEST(GltfLoaderErrors, SparseAccessorIsRejected) {
  const std::string json =
      replaced(triangleGltf(), R"("count":3,"type":"VEC3")",
               R"("count":3,"type":"VEC3","sparse":{"count":1,"indices":{"bufferView":1,
"componentType":5123},"values":{"bufferView":0}})");
  EXPECT_NE(loadError(writeGltf("sparse.gltf", json)).find("sparse"), std::string::npos);
}

TEST(GltfLoaderErrors, IndexOutOfRange) {
  std::string b;
  append<float>(b, {0, 0, 0, 1, 0, 0, 0, 1, 0});
  append<uint16_t>(b, {0, 1, 7});
  const std::string error = loadError(writeGltf("index.gltf", triangleGltf(b)));
  EXPECT_NE(error.find("index 7"), std::string::npos) << error;
}

TEST(GltfLoaderErrors, NanVertex) {
  const std::string error =
      loadError(writeGltf("nan.gltf", triangleGltf(triangleBuffer(std::nanf("")))));
  EXPECT_NE(error.find("non-finite POSITION"), std::string::npos) << error;
}

// Normals are normalised whatever their magnitude: 1e30 squared overflows float and 1e-30
// squared underflows it, so a plain v / length(v) gave 0 (found by the glTF fuzz test).
TEST(GltfLoader, HugeAndTinyNormalsBecomeUnitNormals) {
  std::string b = triangleBuffer();
  append<uint16_t>(b, {0});  // pad the indices to 4 bytes
  append<float>(b, {0, 0, 1e30f, 0, 3e-30f, 0, 4e-30f, 0, 3e-30f});
  std::string json = replaced(triangleGltf(b), R"("POSITION":0})", R"("POSITION":0,"NORMAL":2})");
  json = replaced(json, R"("byteLength":6}])",
                  R"("byteLength":6},{"buffer":0,"byteOffset":44,"byteLength":36}])");
  json = replaced(json, R"("type":"SCALAR"}])",
                  R"("type":"SCALAR"},{"bufferView":2,"componentType":5126,"count":3,)"
                  R"("type":"VEC3"}])");
  const Scene scene = loadGltf(writeGltf("normals.gltf", json));
  ASSERT_EQ(scene.meshes.size(), 1u);
  const auto& n = scene.meshes[0].normals;
  ASSERT_EQ(n.size(), 3u);
  // Float rounding of one division by the largest component and one by a length in
  // [1, sqrt 3]: a few ulps.
  EXPECT_NEAR(n[0].z, 1.0f, 1e-6f);
  EXPECT_NEAR(n[1].y, 1.0f, 1e-6f);
  EXPECT_NEAR(n[2].x, 0.8f, 1e-6f);
  EXPECT_NEAR(n[2].z, 0.6f, 1e-6f);
}

TEST(GltfLoaderErrors, ZeroAreaOnlyMesh) {
  std::string b;
  append<float>(b, {1, 1, 1, 1, 1, 1, 1, 1, 1});
  append<uint16_t>(b, {0, 1, 2});
  const std::string error = loadError(writeGltf("flat.gltf", triangleGltf(b)));
  EXPECT_NE(error.find("zero area"), std::string::npos) << error;
}

TEST(GltfLoaderErrors, BadReferences) {
  const std::string mesh = replaced(triangleGltf(), R"({"mesh":0,)", R"({"mesh":5,)");
  EXPECT_NE(loadError(writeGltf("mesh.gltf", mesh)).find("mesh index 5"), std::string::npos);
  const std::string material =
      replaced(triangleGltf(), R"("indices":1)", R"("indices":1,"material":3)");
  EXPECT_NE(loadError(writeGltf("material.gltf", material)).find("material index 3"),
            std::string::npos);
  const std::string node = replaced(triangleGltf(), R"("nodes":[0])", R"("nodes":[4])");
  EXPECT_NE(loadError(writeGltf("node.gltf", node)).find("node index 4"), std::string::npos);
  const std::string accessor = replaced(triangleGltf(), R"("indices":1)", R"("indices":9)");
  EXPECT_NE(loadError(writeGltf("acc.gltf", accessor)).find("out of"), std::string::npos);
}

// Values outside glTF 2.0's ranges are errors naming the object: a spot whose inner cone
// exceeds its outer, negative or float-overflowing light, a camera with znear <= 0 or zfar
// <= znear, a zero rotation quaternion.
TEST(GltfLoaderErrors, ValuesOutsideTheSpecsRanges) {
  const auto withNode = [](const std::string& node, const std::string& top) {
    return replaced(triangleGltf(), R"("scenes":[{"nodes":[0]}],
"nodes":[{"mesh":0,"name":"tri"}],)",
                    R"("scenes":[{"nodes":[0,1]}],"nodes":[{"mesh":0,"name":"tri"},)" + node +
                        "]," + (top.empty() ? "" : top + ","));
  };
  const std::string lamp = R"({"name":"n","extensions":{"KHR_lights_punctual":{"light":0}}})";
  const auto light = [&](const std::string& body) {
    return withNode(
        lamp, R"("extensions":{"KHR_lights_punctual":{"lights":[{"name":"l",)" + body + "}]}}");
  };
  const auto camera = [&](const std::string& perspective) {
    return withNode(
        R"({"name":"n","camera":0})",
        R"("cameras":[{"name":"c","type":"perspective","perspective":{)" + perspective + "}}]");
  };
  const struct {
    std::string json, message;
  } cases[] = {
      {light(R"("type":"spot","spot":{"innerConeAngle":0.6,"outerConeAngle":0.5})"),
       "light 'l': spot cone angles must be 0 <= inner < outer <= pi/2"},
      {light(R"("type":"spot","spot":{"outerConeAngle":2.0})"), "spot cone angles"},
      {light(R"("type":"point","intensity":-1)"), "light 'l': colour and intensity must be >= 0"},
      {light(R"("type":"point","intensity":3e38)"), "at most 1e20"},
      {light(R"("type":"point","color":[1,-1,0])"), "colour and intensity must be >= 0"},
      {camera(R"("yfov":1,"znear":0)"), "camera 'c': needs 0 < yfov < pi, znear > 0"},
      {camera(R"("yfov":1,"znear":-0.1)"), "znear > 0"},
      {camera(R"("yfov":1,"znear":1,"zfar":0.5)"), "zfar > znear"},
      {camera(R"("yfov":4,"znear":0.1)"), "0 < yfov < pi"},
      {camera(R"("yfov":1e-46,"znear":0.1)"), "0 < yfov < pi"},  // 0 as a float
      {camera(R"("yfov":1,"znear":1e-46)"), "znear > 0"},
      {withNode(R"({"name":"n","mesh":0,"rotation":[0,0,0,0]})", ""),
       "rotation is not a unit quaternion"},
  };
  int i = 0;
  for (const auto& c : cases) {
    const std::string error = loadError(writeGltf("range" + std::to_string(i++) + ".gltf", c.json));
    EXPECT_NE(error.find(c.message), std::string::npos) << error;
  }
  // Inside the ranges they load: a slightly non-unit quaternion is normalised.
  EXPECT_NO_THROW(loadGltf(writeGltf(
      "in_range.gltf", withNode(R"({"name":"n","mesh":0,"rotation":[0,0,0,1.001]})", ""))));
}

// Material factors outside glTF 2.0's ranges are errors naming the material: a base colour
// or metallic above 1 reflects more light than arrives (every bounce multiplies it), and a
// roughness of 1e39 is inf in float. HDR emission (factor above 1) is radiance and loads.
TEST(GltfLoaderErrors, MaterialFactorsOutsideTheirRanges) {
  const auto withMaterial = [](const std::string& material) {
    return replaced(replaced(triangleGltf(), R"("indices":1)", R"("indices":1,"material":0)"),
                    R"("buffers":)",
                    R"("materials":[{"name":"m",)" + material + R"(}],"buffers":)");
  };
  const struct {
    std::string json, message;
  } cases[] = {
      {R"("pbrMetallicRoughness":{"baseColorFactor":[1.5,1,1,1]})",
       "material 'm': baseColorFactor must be in [0, 1]"},
      {R"("pbrMetallicRoughness":{"baseColorFactor":[1,-0.1,1,1]})", "baseColorFactor"},
      {R"("pbrMetallicRoughness":{"metallicFactor":-1})",
       "material 'm': metallicFactor and roughnessFactor must be in [0, 1]"},
      {R"("pbrMetallicRoughness":{"roughnessFactor":1e39})", "roughnessFactor must be in"},
      {R"("occlusionTexture":{"index":0,"strength":2})", "occlusion strength must be in [0, 1]"},
      {R"("alphaMode":"MASK","alphaCutoff":-0.5)", "alphaCutoff must be >= 0"},
      {R"("emissiveFactor":[1,-1,0])", "emissive factor and strength must be >= 0"},
      {R"("emissiveFactor":[1e30,0,0])", "at most 1e20"},
      {R"("emissiveTexture":{"index":0,"extensions":{"KHR_texture_transform":{"scale":[1e39,1]}}})",
       "material 'm' emissiveTexture: KHR_texture_transform offset, rotation and scale must be "
       "finite"},
  };
  int i = 0;
  for (const auto& c : cases) {
    const std::string error =
        loadError(writeGltf("material" + std::to_string(i++) + ".gltf", withMaterial(c.json)));
    EXPECT_NE(error.find(c.message), std::string::npos) << error;
  }
  const Scene hdr = loadGltf(writeGltf("hdr.gltf", withMaterial(R"("emissiveFactor":[4,2,1])")));
  EXPECT_EQ(hdr.materials.at(0).emission(), glm::vec3(4, 2, 1));
}

// A member of the wrong type is an error naming it: tinygltf alone drops such a member and
// loads the file as if it were absent (core/gltf_json_types.h).
TEST(GltfLoaderErrors, MembersOfTheWrongTypeAreErrorsNamingThem) {
  const std::string node = R"("nodes":[{"mesh":0,"name":"tri"}])";
  const auto withNode = [&](const std::string& members) {
    return replaced(triangleGltf(), node, R"("nodes":[{"mesh":0,"name":"tri",)" + members + "}]");
  };
  const auto withMaterial = [&](const std::string& material) {
    return replaced(replaced(triangleGltf(), R"("indices":1)", R"("indices":1,"material":0)"),
                    R"("buffers":)", R"("materials":[)" + material + R"(],"buffers":)");
  };
  const struct {
    std::string json, message;
  } cases[] = {
      {withNode(R"("translation":"abc")"),
       "nodes[0].translation: expected an array of 3 numbers, got a string"},
      {withNode(R"("rotation":[0,0,1])"),
       "nodes[0].rotation: expected an array of 4 numbers, got an array of 3 numbers"},
      {withNode(R"("scale":[1,"2",1])"),
       "nodes[0].scale: expected an array of 3 numbers, got "
       "an array of 3 values"},
      {withNode(R"("children":[0.5])"), "nodes[0].children: expected an array of integers"},
      {replaced(triangleGltf(), R"("mesh":0)", R"("mesh":"0")"),
       "nodes[0].mesh: expected an integer, got a string"},
      {replaced(triangleGltf(), R"("mesh":0)", R"("mesh":0.5)"),
       "nodes[0].mesh: expected an integer, got the number 0.5"},
      {replaced(triangleGltf(), R"("POSITION":0)", R"("POSITION":null)"),
       "meshes[0].primitives[0].attributes: expected an object of integers"},
      {withMaterial(R"({"doubleSided":"yes"})"),
       "materials[0].doubleSided: expected true or false, got a string"},
      {withMaterial(R"({"pbrMetallicRoughness":{"baseColorFactor":[1,1,1]}})"),
       "materials[0].pbrMetallicRoughness.baseColorFactor: expected an array of 4 numbers"},
      {withMaterial(R"({"emissiveTexture":{"index":0,"extensions":{"KHR_texture_transform":)"
                    R"({"offset":[0.5]}}}})"),
       "materials[0].emissiveTexture.extensions.KHR_texture_transform.offset: expected an array "
       "of 2 numbers"},
      {replaced(triangleGltf(), R"("count":3,"type":"SCALAR")", R"("count":"3","type":"SCALAR")"),
       "accessors[1].count: expected an integer, got a string"},
      {withNode(R"("extensions":{"KHR_lights_punctual":{"light":[0]}})"),
       "nodes[0].extensions.KHR_lights_punctual.light: expected an integer, got an array"},
      {replaced(triangleGltf(), R"("scene":0,)",
                R"("scene":0,"extensions":{"KHR_lights_punctual":{"lights":[{"type":"point",)"
                R"("intensity":"bright"}]}},)"),
       "extensions.KHR_lights_punctual.lights[0].intensity: expected a number, got a string"},
      {"[1, 2]", "the glTF JSON is an array of 2 numbers, not an object"},
  };
  int i = 0;
  for (const auto& c : cases) {
    const std::string error = loadError(writeGltf("type" + std::to_string(i++) + ".gltf", c.json));
    EXPECT_NE(error.find(c.message), std::string::npos) << error;
  }
  // The same check reads a .glb's JSON chunk (§4.4: header, then the chunk padded to 4).
  std::string json = withNode(R"("translation":{"x":1})");
  json.append((4 - json.size() % 4) % 4, ' ');
  std::string glb = "glTF";
  append<uint32_t>(glb, {2u, uint32_t(20 + json.size()), uint32_t(json.size()), 0x4E4F534Au});
  const std::string error = loadError(writeGltf("type.glb", glb + json));
  EXPECT_NE(error.find("nodes[0].translation: expected an array of 3 numbers, got an object"),
            std::string::npos)
      << error;
  // Members photovr does not read are not checked.
  EXPECT_NO_THROW(loadGltf(writeGltf(
      "type_ok.gltf", withNode(R"("translation":[1,2,3],"extras":{"translation":"abc"})"))));
}

TEST(GltfLoaderErrors, NodeCycle) {
  const std::string json = replaced(triangleGltf(), R"("nodes":[{"mesh":0,"name":"tri"}])",
                                    R"("nodes":[{"mesh":0,"children":[1]},{"children":[0]}])");
  EXPECT_NE(loadError(writeGltf("cycle.gltf", json)).find("cycle"), std::string::npos);
}

// Issue 23: a file 1e7 m out, where floats are 1 m apart. Its two triangles 0.3 m apart
// kept that offset only to the metre when the loader composed in float; composed in double
// and re-based at the content's centre, they keep it to float precision at the origin.
TEST(GltfLoader, FarAwayFileIsRebasedWithItsPrecision) {
  const std::string nodes =
      R"("nodes":[{"translation":[10000000.25,0,-10000000],"children":[1,2]},{"mesh":0},)"
      R"({"mesh":0,"translation":[0.3,0,0]}])";
  const std::string path = writeGltf(
      "far.gltf", replaced(triangleGltf(), R"("nodes":[{"mesh":0,"name":"tri"}])", nodes));
  const Scene s = loadGltf(path);
  ASSERT_EQ(s.instances.size(), 2u);
  const glm::vec3 a(s.instances[0].transform[3]), b(s.instances[1].transform[3]);
  // Both translations are below 1 m after re-basing: their floats are within 2^-24 m.
  EXPECT_NEAR(b.x - a.x, 0.3f, 1e-6f);
  EXPECT_NEAR(glm::length(a), 0.0f, 1.0f);
  // The origin names the file's place: to the float rounding of a (below 2^-24 m).
  EXPECT_NEAR(s.origin.x + double(a.x), 10000000.25, 1e-7);
  EXPECT_NEAR(s.origin.z + double(a.z), -1e7, 1e-7);
  for (const std::string& w : analyzeScene(s).warnings)
    EXPECT_EQ(w.find("from the origin"), std::string::npos) << w;
  EXPECT_NE(describeScene(s).find("origin: the file's (10000000.9"), std::string::npos)
      << describeScene(s);
  // Export writes it back where it was: read again, the same origin and placement.
  const std::string copy = (testDir() / "far_copy.glb").string();
  writeGlb(s, copy);
  // Read again, the centre is recomputed from double sums of floats: equal to rounding.
  const Scene again = loadGltf(copy);
  EXPECT_NEAR(glm::length(again.origin - s.origin), 0.0, 1e-6);
  const glm::dvec3 placedThen = s.origin + glm::dvec3(s.instances[1].transform[3]);
  const glm::dvec3 placedNow = again.origin + glm::dvec3(again.instances[1].transform[3]);
  EXPECT_NEAR(glm::length(placedNow - placedThen), 0.0, 1e-6);
}

// A file near its zero is left where it is: its coordinates are the file's.
TEST(GltfLoader, NearbyFileIsNotRebased) {
  const std::string nodes = R"("nodes":[{"translation":[3,0,-5],"mesh":0}])";
  const Scene s = loadGltf(writeGltf(
      "near.gltf", replaced(triangleGltf(), R"("nodes":[{"mesh":0,"name":"tri"}])", nodes)));
  EXPECT_EQ(s.origin, glm::dvec3(0.0));
  EXPECT_EQ(glm::vec3(s.instances[0].transform[3]), glm::vec3(3, 0, -5));
}

TEST(GltfLoader, VeryDeepHierarchyLoadsWithoutStackOverflow) {
  std::string nodes = R"("nodes":[)";
  const int depth = 20000;
  for (int i = 0; i < depth; ++i)
    nodes += R"({"translation":[0,1,0],"children":[)" + std::to_string(i + 1) + "]},";
  nodes += R"({"mesh":0}])";
  const std::string json = replaced(triangleGltf(), R"("nodes":[{"mesh":0,"name":"tri"}])", nodes);
  const Scene scene = loadGltf(writeGltf("deep.gltf", json));
  ASSERT_EQ(scene.instances.size(), 1u);
  // Exact: sums of 1.0 stay integers. 20 km up, floats are 2 mm apart, far coarser than
  // the 1 m triangle needs: the scene is re-based at its centre, and the origin says where.
  const glm::vec4 t = scene.instances[0].transform[3];
  EXPECT_EQ(glm::dvec3(t) + scene.origin, glm::dvec3(0, depth, 0));
  EXPECT_LT(glm::length(glm::vec3(t)), 1.0f);
}

TEST(GltfLoaderErrors, NoMeshes) {
  const std::string json =
      replaced(triangleGltf(), R"({"mesh":0,"name":"tri"})", R"({"name":"empty"})");
  EXPECT_NE(loadError(writeGltf("nomesh.gltf", json)).find("contains no triangle meshes"),
            std::string::npos);
}

// A triangle whose one material carries the given "extensions" object.
std::string materialExtensionsGltf(const std::string& extensions) {
  std::string json = replaced(triangleGltf(), R"("indices":1})", R"("indices":1,"material":0})");
  return replaced(json, R"("buffers":)",
                  R"("materials":[{"name":"m","extensions":)" + extensions + R"(}],"buffers":)");
}

TEST(GltfLoader, DielectricExtensionsReachTheMaterial) {
  const std::string json = materialExtensionsGltf(R"({
"KHR_materials_ior":{"ior":1.33},
"KHR_materials_specular":{"specularFactor":0.5,"specularColorFactor":[1,0.5,0.25]},
"KHR_materials_transmission":{"transmissionFactor":0.75},
"KHR_materials_volume":{"thicknessFactor":0.1,"attenuationDistance":2,
                        "attenuationColor":[0.5,1,0.25]}})");
  const Scene scene = loadGltf(writeGltf("dielectric.gltf", json));
  ASSERT_EQ(scene.materials.size(), 1u);
  const Material& m = scene.materials[0];
  EXPECT_FLOAT_EQ(m.ior, 1.33f);
  EXPECT_FLOAT_EQ(m.specularFactor, 0.5f);
  EXPECT_EQ(m.specularColorFactor, glm::vec3(1.0f, 0.5f, 0.25f));
  EXPECT_FLOAT_EQ(m.transmissionFactor, 0.75f);
  EXPECT_FALSE(m.thinWalled());
  EXPECT_FALSE(m.cullsBackFaces());  // a volume's back faces are where light leaves
  // Beer-Lambert: exp(-sigma d) reaches the attenuation colour at d = attenuationDistance.
  const glm::vec3 sigma = m.absorption();
  EXPECT_NEAR(std::exp(-sigma.r * 2.0f), 0.5f, 1e-6f);
  EXPECT_EQ(sigma.g, 0.0f);
  EXPECT_NEAR(std::exp(-sigma.b * 2.0f), 0.25f, 1e-6f);
  EXPECT_NEAR(m.iorF0(), std::pow(0.33 / 2.33, 2.0), 1e-7);
  for (const std::string& w : scene.warnings)
    EXPECT_EQ(w.find("unsupported"), std::string::npos) << w;
}

TEST(GltfLoader, CoreIorGivesExactlyTheCoreF0) {
  // The default ior 1.5 must give the float 0.04 the core model used, so that scenes
  // without the extension render bit-identically to before it was read.
  EXPECT_EQ(Material{}.iorF0(), 0.04f);
}

TEST(GltfLoader, DielectricExtensionsOutOfRangeAreErrors) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"KHR_materials_ior":{"ior":0.5}})", "ior must be 0 or in [1, 10]"},
      {R"({"KHR_materials_specular":{"specularFactor":2}})", "KHR_materials_specular factor"},
      {R"({"KHR_materials_transmission":{"transmissionFactor":-1}})",
       "KHR_materials_transmission factor"},
      {R"({"KHR_materials_volume":{"thicknessFactor":1,"attenuationDistance":-3}})",
       "KHR_materials_volume"},
      {R"({"KHR_materials_ior":{"ior":"glass"}})", "ior"}};
  for (const auto& [extensions, message] : cases) {
    const std::string error =
        loadError(writeGltf("bad_dielectric.gltf", materialExtensionsGltf(extensions)));
    EXPECT_NE(error.find(message), std::string::npos) << extensions << ": " << error;
  }
}

TEST(GltfLoader, VolumeThicknessTextureIsAWarning) {
  const Scene scene = loadGltf(writeGltf(
      "thickness.gltf", materialExtensionsGltf(R"({"KHR_materials_volume":{"thicknessFactor":1,
"thicknessTexture":{"index":0}}})")));
  EXPECT_TRUE(anyContains(scene.warnings, "material 'm'", "thicknessTexture is not used"));
}

TEST(GltfLoader, SheenAndClearcoatReachTheMaterial) {
  const Scene scene = loadGltf(writeGltf("layers.gltf", materialExtensionsGltf(R"({
"KHR_materials_sheen":{"sheenColorFactor":[0.5,0.25,1],"sheenRoughnessFactor":0.3},
"KHR_materials_clearcoat":{"clearcoatFactor":0.75,"clearcoatRoughnessFactor":0.125}})")));
  ASSERT_EQ(scene.materials.size(), 1u);
  const Material& m = scene.materials[0];
  EXPECT_EQ(m.sheenColorFactor, glm::vec3(0.5f, 0.25f, 1.0f));
  EXPECT_FLOAT_EQ(m.sheenRoughnessFactor, 0.3f);
  EXPECT_FLOAT_EQ(m.clearcoatFactor, 0.75f);
  EXPECT_FLOAT_EQ(m.clearcoatRoughnessFactor, 0.125f);
  EXPECT_TRUE(scene.warnings.empty());
  EXPECT_NE(describeScene(scene).find("clear-coated 1, sheen 1"), std::string::npos);
}

TEST(GltfLoader, SheenAndClearcoatOutOfRangeAreErrors) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"KHR_materials_sheen":{"sheenColorFactor":[2,0,0]}})", "KHR_materials_sheen"},
      {R"({"KHR_materials_sheen":{"sheenRoughnessFactor":-0.5}})", "KHR_materials_sheen"},
      {R"({"KHR_materials_clearcoat":{"clearcoatFactor":1.5}})", "KHR_materials_clearcoat"},
      {R"({"KHR_materials_clearcoat":{"clearcoatRoughnessFactor":"x"}})",
       "clearcoatRoughnessFactor"}};
  for (const auto& [extensions, message] : cases) {
    const std::string error =
        loadError(writeGltf("bad_layers.gltf", materialExtensionsGltf(extensions)));
    EXPECT_NE(error.find(message), std::string::npos) << extensions << ": " << error;
  }
}

TEST(GltfLoader, ClearcoatNormalTextureAndItsScaleAreRead) {
  // A flat normal map (128, 128, 255) for the coat to name; the triangle file has none.
  const fs::path dir = testDir();
  Image8 image(1, 1, 4);
  const uint8_t flat[4] = {128, 128, 255, 255};
  std::memcpy(image.data.data(), flat, 4);
  writeImage((dir / "flat_normal.png").string(), image);
  std::string json = materialExtensionsGltf(R"({"KHR_materials_clearcoat":{
"clearcoatFactor":1,"clearcoatNormalTexture":{"index":0,"scale":0.5}}})");
  json = replaced(json, R"("buffers":)",
                  R"("textures":[{"source":0}],"images":[{"uri":"flat_normal.png"}],"buffers":)");
  writeFile(dir / "coat_normal.gltf", json);
  const Scene scene = loadGltf((dir / "coat_normal.gltf").string());
  ASSERT_EQ(scene.materials.size(), 1u);
  const Material& m = scene.materials[0];
  EXPECT_EQ(m.clearcoatNormalTexture.texture, 0);
  EXPECT_FLOAT_EQ(m.clearcoatNormalScale, 0.5f);
  EXPECT_FALSE(anyContains(scene.warnings, "clearcoatNormalTexture"));
}

TEST(GltfLoader, UnlitIsRead) {
  const Scene scene =
      loadGltf(writeGltf("unlit.gltf", materialExtensionsGltf(R"({"KHR_materials_unlit":{}})")));
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_TRUE(scene.materials[0].unlit);
  EXPECT_FALSE(scene.materials[0].isEmissive());
}

TEST(GltfLoader, InfoListsEachExtensionReadOrIgnored) {
  std::string json = materialExtensionsGltf(R"({"KHR_materials_ior":{"ior":1.4}})");
  json =
      replaced(json, R"("scene":0,)",
               R"("extensionsUsed":["KHR_materials_ior","KHR_materials_iridescence"],"scene":0,)");
  const Scene scene = loadGltf(writeGltf("extensions.gltf", json));
  const std::string info = describeScene(scene);
  EXPECT_NE(info.find("extensions: KHR_materials_ior (read) KHR_materials_iridescence (ignored)"),
            std::string::npos)
      << info;
}

}  // namespace
}  // namespace photovr
