// KHR_draco_mesh_compression (issue 23): files written here with libdraco's own encoder,
// loaded by photovr, against the mesh before compression within the codec's quantisation.
#include <gtest/gtest.h>

#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/gltf_loader.h"
#include "core/mesh_gen.h"
#include "tests/core/glb_file.h"
#include "tests/core/test_dir.h"

namespace photovr {
namespace {

namespace fs = std::filesystem;

// Quantisation bits per attribute (the encoder's settings below).
constexpr int kPositionBits = 14, kNormalBits = 10, kUvBits = 12;

template <int N>
int addAttribute(draco::Mesh& dm, draco::GeometryAttribute::Type type,
                 const std::vector<glm::vec<N, float>>& values) {
  draco::GeometryAttribute ga;
  ga.Init(type, nullptr, N, draco::DT_FLOAT32, false, sizeof(float) * N, 0);
  const int id = dm.AddAttribute(ga, true, uint32_t(values.size()));
  for (size_t i = 0; i < values.size(); ++i)
    dm.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(uint32_t(i)), &values[i][0]);
  return int(dm.attribute(id)->unique_id());
}

struct Encoded {
  std::string bytes;
  int position = 0, normal = 0, uv = 0;  // Draco unique ids
};

Encoded encode(const Mesh& m) {
  draco::Mesh dm;
  dm.set_num_points(uint32_t(m.positions.size()));
  Encoded e;
  e.position = addAttribute<3>(dm, draco::GeometryAttribute::POSITION, m.positions);
  e.normal = addAttribute<3>(dm, draco::GeometryAttribute::NORMAL, m.normals);
  e.uv = addAttribute<2>(dm, draco::GeometryAttribute::TEX_COORD, m.uv0);
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    draco::Mesh::Face f;
    for (int k = 0; k < 3; ++k) f[k] = draco::PointIndex(m.indices[t + size_t(k)]);
    dm.AddFace(f);
  }
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, kPositionBits);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, kNormalBits);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, kUvBits);
  draco::EncoderBuffer out;
  const draco::Status status = encoder.EncodeMeshToBuffer(dm, &out);
  EXPECT_TRUE(status.ok()) << status.error_msg_string();
  e.bytes.assign(out.data(), out.size());
  return e;
}

// A glTF whose one primitive is Draco-compressed, as exporters write it: accessors with
// no bufferView, the bitstream in buffer 0 through bufferView 0. 'uri' names the buffer
// (absent: the GLB's own).
std::string dracoJson(const Encoded& e, size_t vertices, size_t indices, const std::string& uri) {
  const std::string n = std::to_string(vertices);
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
"extensionsUsed":["KHR_draco_mesh_compression"],
"extensionsRequired":["KHR_draco_mesh_compression"],
"meshes":[{"name":"ball","primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2},
 "indices":3,"extensions":{"KHR_draco_mesh_compression":{"bufferView":0,
 "attributes":{"POSITION":)" +
         std::to_string(e.position) + R"(,"NORMAL":)" + std::to_string(e.normal) +
         R"(,"TEXCOORD_0":)" + std::to_string(e.uv) + R"(}}}}]}],
"buffers":[{"byteLength":)" +
         std::to_string(e.bytes.size()) + (uri.empty() ? "" : R"(,"uri":")" + uri + "\"") +
         R"(}],
"bufferViews":[{"buffer":0,"byteLength":)" +
         std::to_string(e.bytes.size()) + R"(}],
"accessors":[{"componentType":5126,"count":)" +
         n + R"(,"type":"VEC3","min":[-1,-1,-1],"max":[1,1,1]},
 {"componentType":5126,"count":)" +
         n + R"(,"type":"VEC3"},{"componentType":5126,"count":)" + n +
         R"(,"type":"VEC2"},
 {"componentType":5125,"count":)" +
         std::to_string(indices) + R"(,"type":"SCALAR"}]})";
}

using testing::glb;

struct Tolerance {
  float position, normal, uv;
};

// Draco quantises each attribute over its range with 'bits' bits: rounding errs by half a
// step; a step is allowed (float margin). Normals are quantised in octahedral coordinates,
// whose step is 2 / (2^bits - 1) over [-1, 1], and mapped back to the sphere, which
// stretches it: with one step of tolerance 60 of the ball's 528 triangles had a normal
// component off by more (measured), with two none.
Tolerance quantisation(float positionRange) {
  return {positionRange / float((1 << kPositionBits) - 1), 4.0f / float((1 << kNormalBits) - 1),
          1.0f / float((1 << kUvBits) - 1)};
}

// Every original triangle is in the decoded mesh (same vertices within tolerance, same
// winding, any rotation); Draco reorders faces and vertices.
void expectSameTriangles(const Mesh& original, const Mesh& decoded, const Tolerance& tol) {
  ASSERT_EQ(decoded.indices.size(), original.indices.size());
  const auto near = [&](uint32_t a, uint32_t b) {
    return glm::all(glm::lessThanEqual(glm::abs(original.positions[a] - decoded.positions[b]),
                                       glm::vec3(tol.position))) &&
           glm::all(glm::lessThanEqual(glm::abs(original.normals[a] - decoded.normals[b]),
                                       glm::vec3(tol.normal))) &&
           glm::all(
               glm::lessThanEqual(glm::abs(original.uv0[a] - decoded.uv0[b]), glm::vec2(tol.uv)));
  };
  int missing = 0;
  for (size_t t = 0; t < original.indices.size(); t += 3) {
    bool found = false;
    for (size_t u = 0; u < decoded.indices.size() && !found; u += 3)
      for (int r = 0; r < 3 && !found; ++r)
        found = near(original.indices[t], decoded.indices[u + size_t(r)]) &&
                near(original.indices[t + 1], decoded.indices[u + size_t((r + 1) % 3)]) &&
                near(original.indices[t + 2], decoded.indices[u + size_t((r + 2) % 3)]);
    missing += !found;
  }
  EXPECT_EQ(missing, 0) << "of " << original.indices.size() / 3 << " triangles";
}

Mesh ball() {
  return makeUvSphere(1.0f, 24, 12);
}

TEST(GltfDraco, GlbDecodesToTheMeshWithinQuantisation) {
  const Mesh m = ball();
  const Encoded e = encode(m);
  const fs::path path = testing::freshTestDir("photovr_gltf_draco") / "ball.glb";
  std::ofstream(path, std::ios::binary)
      << glb(dracoJson(e, m.positions.size(), m.indices.size(), ""), e.bytes);
  const Scene s = loadGltf(path.string());
  ASSERT_EQ(s.meshes.size(), 1u);
  expectSameTriangles(m, s.meshes[0], quantisation(2.0f));
}

TEST(GltfDraco, GltfWithAnExternalBufferDecodesToo) {
  const Mesh m = ball();
  const Encoded e = encode(m);
  const fs::path dir = testing::freshTestDir("photovr_gltf_draco");
  std::ofstream(dir / "ball.bin", std::ios::binary) << e.bytes;
  std::ofstream(dir / "ball.gltf")
      << dracoJson(e, m.positions.size(), m.indices.size(), "ball.bin");
  const Scene s = loadGltf((dir / "ball.gltf").string());
  ASSERT_EQ(s.meshes.size(), 1u);
  expectSameTriangles(m, s.meshes[0], quantisation(2.0f));
  // The power of the comparison: a tolerance 10x tighter than one step finds moved vertices.
  const Tolerance tight = {quantisation(2.0f).position / 10.0f, 1.0f, 1.0f};
  const Mesh& d = s.meshes[0];
  int moved = 0;
  for (size_t i = 0; i < d.positions.size(); ++i) {
    float best = 1e9f;
    for (const glm::vec3& p : m.positions) best = std::min(best, glm::length(p - d.positions[i]));
    moved += best > tight.position;
  }
  EXPECT_GT(moved, 0) << "quantisation left every vertex exact: the test cannot see it";
}

// A bitstream cut short, or bytes flipped, fail with one line naming the file and the
// primitive, never a crash (the ASan build runs this).
TEST(GltfDraco, BrokenBitstreamsFailWithOneLine) {
  const Mesh m = ball();
  const Encoded good = encode(m);
  const fs::path dir = testing::freshTestDir("photovr_gltf_draco");
  int refused = 0;
  for (int k = 0; k < 60; ++k) {
    Encoded e = good;
    if (k < 20) {
      e.bytes.resize(e.bytes.size() * size_t(k) / 20);
    } else {
      for (int j = 0; j < 4; ++j) e.bytes[size_t(k * 7919 + j * 104729) % e.bytes.size()] ^= 0x5A;
    }
    if (e.bytes.empty()) e.bytes = "x";
    const fs::path path = dir / "broken.glb";
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        << glb(dracoJson(e, m.positions.size(), m.indices.size(), ""), e.bytes);
    try {
      loadGltf(path.string());
    } catch (const InputError& err) {
      const std::string what = err.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      EXPECT_NE(what.find("broken.glb"), std::string::npos) << what;
      ++refused;
    }
  }
  EXPECT_GE(refused, 20) << "every truncated bitstream is refused";
}

}  // namespace
}  // namespace photovr
