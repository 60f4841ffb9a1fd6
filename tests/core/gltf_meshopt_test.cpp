// EXT_meshopt_compression (issue 23): files written here with libmeshoptimizer's own
// encoders, loaded by photovr, against the mesh before compression. The vertex and index
// codecs are lossless, so what they carry comes back bit for bit; the filters quantise, and
// their tolerance is derived from the bits given to the encoder.
#include <gtest/gtest.h>

#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>
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
using testing::glb;

constexpr int kNormalBits = 12;    // octahedral filter, 16-bit components
constexpr int kPositionBits = 16;  // exponential filter mantissa

// One compressed stream and the view it decodes into.
struct Stream {
  std::string bytes;
  size_t count = 0, stride = 0;
  std::string mode, filter = "NONE";
};

template <typename T>
Stream vertexStream(const std::vector<T>& data, size_t stride, const std::string& filter) {
  Stream s{std::string(meshopt_encodeVertexBufferBound(data.size(), stride), '\0'), data.size(),
           stride, "ATTRIBUTES", filter};
  s.bytes.resize(meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(s.bytes.data()),
                                            s.bytes.size(), data.data(), data.size(), stride));
  return s;
}

Stream indexStream(const std::vector<uint32_t>& indices, bool sequence, size_t vertices) {
  Stream s;
  s.count = indices.size();
  s.stride = 4;
  s.mode = sequence ? "INDICES" : "TRIANGLES";
  s.bytes.resize(sequence ? meshopt_encodeIndexSequenceBound(indices.size(), vertices)
                          : meshopt_encodeIndexBufferBound(indices.size(), vertices));
  unsigned char* out = reinterpret_cast<unsigned char*>(s.bytes.data());
  s.bytes.resize(
      sequence ? meshopt_encodeIndexSequence(out, s.bytes.size(), indices.data(), indices.size())
               : meshopt_encodeIndexBuffer(out, s.bytes.size(), indices.data(), indices.size()));
  return s;
}

// Positions through the exponential filter: 3 floats a vertex sharing one exponent.
Stream exponentialPositions(const Mesh& m) {
  std::vector<float> filtered(m.positions.size() * 3);
  meshopt_encodeFilterExp(filtered.data(), m.positions.size(), 12, kPositionBits,
                          &m.positions[0].x);
  std::vector<std::array<float, 3>> rows(m.positions.size());
  std::memcpy(rows.data(), filtered.data(), filtered.size() * sizeof(float));
  return vertexStream(rows, 12, "EXPONENTIAL");
}

// Normals through the octahedral filter: int16 x, y, z (normalized) and w.
Stream octahedralNormals(const Mesh& m) {
  std::vector<float> xyzw;
  for (const glm::vec3& n : m.normals) xyzw.insert(xyzw.end(), {n.x, n.y, n.z, 0.0f});
  std::vector<std::array<int16_t, 4>> rows(m.normals.size());
  meshopt_encodeFilterOct(rows.data(), rows.size(), 8, kNormalBits, xyzw.data());
  return vertexStream(rows, 8, "OCTAHEDRAL");
}

// A glTF whose every view is meshopt-compressed, as gltfpack writes it: the streams one
// after another in buffer 0 (the GLB's own, or 'uri'), the views in buffer 1, a fallback
// with no data. Accessors: POSITION 0, NORMAL 1 (SHORT normalized), TEXCOORD_0 2, indices 3.
std::string meshoptJson(const std::vector<Stream>& streams, const std::string& uri) {
  std::string views, compressed;
  size_t fallbackOffset = 0;
  for (const Stream& s : streams) {
    const size_t decoded = s.count * s.stride;
    views += std::string(views.empty() ? "" : ",") + R"({"buffer":1,"byteOffset":)" +
             std::to_string(fallbackOffset) + R"(,"byteLength":)" + std::to_string(decoded) +
             (s.mode == "ATTRIBUTES" ? R"(,"byteStride":)" + std::to_string(s.stride) : "") +
             R"(,"extensions":{"EXT_meshopt_compression":{"buffer":0,"byteOffset":)" +
             std::to_string(compressed.size()) + R"(,"byteLength":)" +
             std::to_string(s.bytes.size()) + R"(,"byteStride":)" + std::to_string(s.stride) +
             R"(,"count":)" + std::to_string(s.count) + R"(,"mode":")" + s.mode +
             R"(","filter":")" + s.filter + R"("}}})";
    compressed += s.bytes;
    while (compressed.size() % 4) compressed.push_back('\0');
    fallbackOffset += (decoded + 3) / 4 * 4;
  }
  const std::string n = std::to_string(streams[0].count);
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
"extensionsUsed":["EXT_meshopt_compression"],"extensionsRequired":["EXT_meshopt_compression"],
"meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2},"indices":3}]}],
"buffers":[{"byteLength":)" +
         std::to_string(compressed.size()) + (uri.empty() ? "" : R"(,"uri":")" + uri + "\"") +
         R"(},{"byteLength":)" + std::to_string(fallbackOffset) +
         R"(,"extensions":{"EXT_meshopt_compression":{"fallback":true}}}],
"bufferViews":[)" +
         views +
         R"(],
"accessors":[{"bufferView":0,"componentType":5126,"count":)" +
         n + R"(,"type":"VEC3","min":[-1,-1,-1],"max":[1,1,1]},
 {"bufferView":1,"componentType":5122,"normalized":true,"count":)" +
         n + R"(,"type":"VEC3"},{"bufferView":2,"componentType":5126,"count":)" + n +
         R"(,"type":"VEC2"},{"bufferView":3,"componentType":5125,"count":)" +
         std::to_string(streams[3].count) + R"(,"type":"SCALAR"}]})";
}

std::string concatenated(const std::vector<Stream>& streams) {
  std::string bin;
  for (const Stream& s : streams) {
    bin += s.bytes;
    while (bin.size() % 4) bin.push_back('\0');
  }
  return bin;
}

Mesh ball() {
  return makeUvSphere(1.0f, 24, 12);
}

std::vector<Stream> streamsOf(const Mesh& m, bool exponential, bool sequence) {
  return {exponential ? exponentialPositions(m) : vertexStream(m.positions, 12, "NONE"),
          octahedralNormals(m), vertexStream(m.uv0, 8, "NONE"),
          indexStream(m.indices, sequence, m.positions.size())};
}

// The octahedral filter keeps 'bits' signed bits of x and y in [-1, 1]: a step of
// 2 / (2^(bits-1) - 1), and mapping back to the sphere can stretch it by up to 2 (the
// fold); stored as int16, read back with 1/32767 more rounding. Two steps allowed.
float normalTolerance() {
  return 2.0f * 2.0f / float((1 << (kNormalBits - 1)) - 1);
}

// The triangles of an index list, each rotated to start at its smallest index: the index
// buffer codec keeps every triangle and its winding but may rotate its corners.
std::vector<std::array<uint32_t, 3>> triangles(const std::vector<uint32_t>& indices) {
  std::vector<std::array<uint32_t, 3>> out;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    std::array<uint32_t, 3> tri = {indices[t], indices[t + 1], indices[t + 2]};
    std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
    out.push_back(tri);
  }
  return out;
}

void expectSameGeometry(const Mesh& original, const Mesh& decoded, float positionTolerance) {
  ASSERT_EQ(decoded.positions.size(), original.positions.size());
  ASSERT_EQ(decoded.normals.size(), original.normals.size());
  ASSERT_EQ(decoded.uv0.size(), original.uv0.size());
  EXPECT_EQ(triangles(decoded.indices), triangles(original.indices));  // lossless
  int positions = 0, normals = 0, uvs = 0;
  for (size_t i = 0; i < original.positions.size(); ++i) {
    positions += glm::any(glm::greaterThan(glm::abs(decoded.positions[i] - original.positions[i]),
                                           glm::vec3(positionTolerance)));
    normals += glm::any(glm::greaterThan(glm::abs(decoded.normals[i] - original.normals[i]),
                                         glm::vec3(normalTolerance())));
    uvs += decoded.uv0[i] != original.uv0[i];  // the vertex codec is lossless
  }
  EXPECT_EQ(positions, 0);
  EXPECT_EQ(normals, 0);
  EXPECT_EQ(uvs, 0);
}

TEST(GltfMeshopt, GlbWithAFallbackBufferDecodesToTheSameMesh) {
  const Mesh m = ball();
  const std::vector<Stream> streams = streamsOf(m, false, false);
  const fs::path path = testing::freshTestDir("photovr_gltf_meshopt") / "ball.glb";
  std::ofstream(path, std::ios::binary) << glb(meshoptJson(streams, ""), concatenated(streams));
  const Scene s = loadGltf(path.string());
  ASSERT_EQ(s.meshes.size(), 1u);
  expectSameGeometry(m, s.meshes[0], 0.0f);  // positions unfiltered: lossless
}

// Positions through the exponential filter (a K-bit mantissa shared by the vertex's three
// components: the largest, below 2^e, is stored to 2^(e - K + 1), so each component errs by
// at most half that), indices as a sequence, the streams in an external .bin.
TEST(GltfMeshopt, FilteredPositionsAndIndexSequenceFromAnExternalBuffer) {
  const Mesh m = ball();
  const std::vector<Stream> streams = streamsOf(m, true, true);
  const fs::path dir = testing::freshTestDir("photovr_gltf_meshopt");
  std::ofstream(dir / "ball.bin", std::ios::binary) << concatenated(streams);
  std::ofstream(dir / "ball.gltf") << meshoptJson(streams, "ball.bin");
  const Scene s = loadGltf((dir / "ball.gltf").string());
  ASSERT_EQ(s.meshes.size(), 1u);
  const float step = std::ldexp(1.0f, 1 - kPositionBits + 1);  // |p| <= 1 < 2^1
  expectSameGeometry(m, s.meshes[0], 0.5f * step);
  // The power of the comparison: the filter moved vertices, and a tenth of the bound sees it.
  int moved = 0;
  for (size_t i = 0; i < m.positions.size(); ++i)
    moved += glm::any(glm::greaterThan(glm::abs(s.meshes[0].positions[i] - m.positions[i]),
                                       glm::vec3(0.05f * step)));
  EXPECT_GT(moved, 0) << "the filter left every vertex exact: the test cannot see it";
}

std::string loadError(const fs::path& path) {
  try {
    loadGltf(path.string());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A stream cut short or with bytes flipped, and views the extension does not allow, fail
// with one line naming the file, never a crash (the ASan build runs this).
TEST(GltfMeshopt, BrokenStreamsFailWithOneLine) {
  const Mesh m = ball();
  const std::vector<Stream> good = streamsOf(m, false, false);
  const fs::path path = testing::freshTestDir("photovr_gltf_meshopt") / "broken.glb";
  int refused = 0;
  for (int k = 0; k < 48; ++k) {
    std::vector<Stream> streams = good;
    Stream& s = streams[size_t(k % 4)];
    if (k < 24)
      s.bytes.resize(s.bytes.size() * size_t(k / 4) / 6);
    else
      for (int j = 0; j < 4; ++j) s.bytes[size_t(k * 7919 + j * 104729) % s.bytes.size()] ^= 0x5A;
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        << glb(meshoptJson(streams, ""), concatenated(streams));
    const std::string error = loadError(path);
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    if (!error.empty()) {
      EXPECT_NE(error.find("broken.glb"), std::string::npos) << error;
    }
    refused += !error.empty();
  }
  EXPECT_GE(refused, 24) << "every truncated stream is refused";
}

TEST(GltfMeshopt, ViewsTheExtensionForbidsAreNamed) {
  const Mesh m = ball();
  const fs::path path = testing::freshTestDir("photovr_gltf_meshopt") / "bad.glb";
  const auto errorWith = [&](auto change) {
    std::vector<Stream> streams = streamsOf(m, false, false);
    change(streams);
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        << glb(meshoptJson(streams, ""), concatenated(streams));
    return loadError(path);
  };
  EXPECT_NE(errorWith([](auto& s) {
              s[0].filter = "OCTAHEDRAL";
            }).find("bufferView 0: EXT_meshopt_compression filter OCTAHEDRAL with byteStride 12"),
            std::string::npos);
  EXPECT_NE(errorWith([](auto& s) { s[3].mode = "STRIPS"; }).find("mode STRIPS"),
            std::string::npos);
  EXPECT_NE(errorWith([](auto& s) { s[3].count -= 1; }).find("not a multiple of 3"),
            std::string::npos);
  EXPECT_NE(
      errorWith([](auto& s) { s[3].stride = 3; }).find("TRIANGLES byteStride 3 is not 2 or 4"),
      std::string::npos);
}

// Bounded fuzzing of the decoder's inputs: the extension's numbers replaced by extremes and
// bytes of the streams flipped. Each file loads into a mesh whose indices are in range, or
// fails with one line naming it; never a crash or a sanitizer report. Fixed seed.
std::string mutated(std::string json, std::string& bin, std::mt19937& rng) {
  static const char* kNumbers[] = {"0",  "1",   "2",   "3",     "4",          "7",     "8",
                                   "12", "255", "256", "65536", "4294967296", "1e300", "-1"};
  if (rng() % 3 == 0) {
    for (int j = 0; j < 3; ++j) bin[rng() % bin.size()] ^= char(1 << (rng() % 8));
    return json;
  }
  for (size_t tries = 0; tries < 100; ++tries) {
    const size_t at = rng() % json.size();
    if (!std::isdigit(static_cast<unsigned char>(json[at]))) continue;
    size_t begin = at, end = at;
    while (begin > 0 && std::isdigit(static_cast<unsigned char>(json[begin - 1]))) --begin;
    while (end < json.size() && std::isdigit(static_cast<unsigned char>(json[end]))) ++end;
    return json.replace(begin, end - begin, kNumbers[rng() % std::size(kNumbers)]);
  }
  return json;
}

TEST(GltfMeshopt, MutatedFilesLoadSoundlyOrFailWithOneLine) {
  const Mesh m = ball();
  const std::vector<Stream> streams = streamsOf(m, true, false);
  const std::string json = meshoptJson(streams, ""), bin = concatenated(streams);
  const fs::path path = testing::freshTestDir("photovr_gltf_meshopt") / "mutant.glb";
  std::mt19937 rng(20261204);
  int loaded = 0, refused = 0;
  for (int it = 0; it < 400; ++it) {
    std::string b = bin;
    const std::string j = mutated(json, b, rng);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << glb(j, b);
    try {
      const Scene s = loadGltf(path.string());
      for (const Mesh& mesh : s.meshes)
        for (uint32_t i : mesh.indices) ASSERT_LT(i, mesh.positions.size()) << j;
      ++loaded;
    } catch (const InputError& e) {
      const std::string what = e.what();
      ASSERT_EQ(what.find('\n'), std::string::npos) << what;
      ASSERT_EQ(what.rfind(path.string(), 0), 0u) << what;
      ++refused;
    }
  }
  // Both outcomes occur: the mutations are neither all harmless nor all fatal.
  EXPECT_GT(loaded, 20);
  EXPECT_GT(refused, 100);
}

}  // namespace
}  // namespace photovr
