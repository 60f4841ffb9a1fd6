// Little- and big-endian field access for HID reports (dk2.md §2-§3: feature and sensor
// reports are little-endian; the packed IMU samples are big-endian 64-bit words).
#pragma once

#include <bit>
#include <cstdint>

namespace photovr::hmd {

inline uint16_t le16(const uint8_t* p) {
  return uint16_t(p[0] | (p[1] << 8));
}
inline uint32_t le32(const uint8_t* p) {
  return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}
inline float leFloat(const uint8_t* p) {
  return std::bit_cast<float>(le32(p));
}

inline void putLe16(uint8_t* p, uint16_t v) {
  p[0] = uint8_t(v);
  p[1] = uint8_t(v >> 8);
}
inline void putLe32(uint8_t* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = uint8_t(v >> (8 * i));
}
inline void putLeFloat(uint8_t* p, float v) {
  putLe32(p, std::bit_cast<uint32_t>(v));
}

}  // namespace photovr::hmd
