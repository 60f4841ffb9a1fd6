// A skinned, animated glTF file written by the test itself (tests/core/skinning_test.cpp
// checks its poses by hand; tests/hybrid/animation_pipeline_test.cpp renders it).
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>

#include "tests/core/glb_file.h"

namespace photovr::testing {

template <typename T>
inline void appendValues(std::string& b, std::initializer_list<T> values) {
  for (T v : values) b.append(reinterpret_cast<const char*>(&v), sizeof v);
}

// A bar of four vertices on joints 0 (root, at the origin) and 1 (tip, at x = 1): A (0,0,0)
// on the root alone, B (2,0,0) and D (2,1,0) on the tip alone, C (1,1,0) half on each. The
// tip turns about z from 0 to 90 degrees over 1 s and holds there until 2 s (then loops). The
// skinned node's own translation (100 m) must be ignored (glTF 2.0 §3.7.3.3). Every normal is +x,
// so turns show in them.
struct SkinOptions {
  int tipJointOfD = 1;        // JOINTS_0 of vertex D
  float weightOfA = 1.0f;     // WEIGHTS_0 x of vertex A
  bool rigidUserToo = false;  // a second, unskinned node uses the same mesh
  bool emissive = false;      // the bar glows (white, strength 1): a picture without lights
};

// Written as bar.glb into 'dir'; returns its path.
inline std::string skinnedFile(const std::filesystem::path& dir, const SkinOptions& o = {}) {
  std::string bin;
  appendValues<float>(bin, {0, 0, 0, 2, 0, 0, 1, 1, 0, 2, 1, 0});  // 0: positions, 48
  appendValues<float>(bin, {1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0});  // 1: normals, 48
  appendValues<uint8_t>(bin, {0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0,  // 2: joints, 16
                              uint8_t(o.tipJointOfD), 0, 0, 0});
  appendValues<float>(bin,
                      {o.weightOfA, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0});  // 3: 64
  appendValues<uint16_t>(bin, {0, 1, 2, 1, 3, 2});                              // 4: indices, 12
  appendValues<float>(bin, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0,  0, 0, 1,    // 5: inverse binds,
                            1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1, 0, 0, 1});  //    128
  appendValues<float>(bin, {0, 1, 2});                                          // 6: times, 12
  appendValues<float>(bin, {0, 0, 0, 1, 0, 0, 0.70710678f, 0.70710678f,         // 7: rotations, 48
                            0, 0, 0.70710678f, 0.70710678f});
  std::string nodes = R"([{"name":"root","children":[1]},{"name":"tip","translation":[1,0,0]},
    {"name":"skinned","mesh":0,"skin":0,"translation":[100,0,0]})";
  std::string roots = "[0,2]";
  if (o.rigidUserToo)
    nodes += R"(,{"name":"rigid","mesh":0,"translation":[0,0,5]})", roots = "[0,2,3]";
  const std::string json = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":)" + roots +
                           R"(}],"nodes":)" + nodes + R"(],
"skins":[{"name":"bar","joints":[0,1],"inverseBindMatrices":5,"skeleton":0}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"JOINTS_0":2,"WEIGHTS_0":3},
  "indices":4)" +
                           std::string(o.emissive ? R"(,"material":0}]}],
"materials":[{"emissiveFactor":[1,1,1],"doubleSided":true}],)"
                                                  : R"(}]}],)") +
                           R"(
"animations":[{"name":"bend","channels":[{"sampler":0,"target":{"node":1,"path":"rotation"}}],
  "samplers":[{"input":6,"output":7}]}],
"buffers":[{"byteLength":376}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":48},
 {"buffer":0,"byteOffset":96,"byteLength":16},{"buffer":0,"byteOffset":112,"byteLength":64},
 {"buffer":0,"byteOffset":176,"byteLength":12},{"buffer":0,"byteOffset":188,"byteLength":128},
 {"buffer":0,"byteOffset":316,"byteLength":12},{"buffer":0,"byteOffset":328,"byteLength":48}],
"accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[2,1,0]},
 {"bufferView":1,"componentType":5126,"count":4,"type":"VEC3"},
 {"bufferView":2,"componentType":5121,"count":4,"type":"VEC4"},
 {"bufferView":3,"componentType":5126,"count":4,"type":"VEC4"},
 {"bufferView":4,"componentType":5123,"count":6,"type":"SCALAR"},
 {"bufferView":5,"componentType":5126,"count":2,"type":"MAT4"},
 {"bufferView":6,"componentType":5126,"count":3,"type":"SCALAR","min":[0],"max":[2]},
 {"bufferView":7,"componentType":5126,"count":3,"type":"VEC4"}]})";
  const auto path = dir / "bar.glb";
  std::ofstream(path, std::ios::binary) << glb(json, bin);
  return path.string();
}

}  // namespace photovr::testing
