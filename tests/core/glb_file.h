// A GLB container (glTF 2.0 §4.4) around a JSON text and a BIN chunk, for tests that write
// their own files: chunks padded to 4 bytes as the format requires.
#pragma once

#include <cstdint>
#include <string>

namespace photovr::testing {

inline void putU32(std::string& s, uint32_t v) {
  for (int k = 0; k < 4; ++k) s.push_back(char(v >> (8 * k)));
}

inline std::string glb(std::string json, std::string bin) {
  while (json.size() % 4) json.push_back(' ');
  while (bin.size() % 4) bin.push_back('\0');
  std::string out = "glTF";
  putU32(out, 2);
  putU32(out, uint32_t(12 + 8 + json.size() + 8 + bin.size()));
  putU32(out, uint32_t(json.size()));
  out += "JSON" + json;
  putU32(out, uint32_t(bin.size()));
  out += std::string("BIN\0", 4) + bin;
  return out;
}

}  // namespace photovr::testing
