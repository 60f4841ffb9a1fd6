// The DK2 sensor report 0x0B (dk2.md §3): raw integer fields, so that encode(decode(b)) is
// byte-exact, plus conversions to SI units.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "hmd/decode_stats.h"

namespace photovr::hmd {

constexpr uint8_t kSensorReportId = 0x0B;
constexpr size_t kSensorReportSize = 64;
using ReportBytes = std::array<uint8_t, kSensorReportSize>;

// Three signed 21-bit values in one big-endian 64-bit word (dk2.md §3).
using Packed21 = std::array<int32_t, 3>;
constexpr int32_t kPacked21Min = -(1 << 20);
constexpr int32_t kPacked21Max = (1 << 20) - 1;
Packed21 unpack21(const uint8_t* bytes);
void pack21(const Packed21& v, uint8_t* bytes);  // clamps each value to 21 bits

struct RawImuSample {
  Packed21 accel{};  // 1e-4 m/s^2
  Packed21 gyro{};   // 1e-4 rad/s
};

struct SensorReport {
  uint16_t commandId = 0;
  uint8_t numSamples = 1;  // > 2: slot 0 averages the first numSamples - 1 samples
  uint16_t sampleCount = 0;
  int16_t temperature = 0;   // 0.01 C
  uint32_t timestampUs = 0;  // of the newest sample
  std::array<RawImuSample, 2> samples{};
  std::array<int16_t, 3> mag{};  // 1e-4 gauss
  uint16_t frameCount = 0;
  uint32_t frameTimestamp = 0;
  uint8_t frameId = 0, ledPhase = 0;
  uint16_t exposureCount = 0;
  uint32_t exposureTimestamp = 0;

  int slotsUsed() const { return numSamples >= 2 ? 2 : 1; }
  float temperatureC() const { return temperature * 0.01f; }
  glm::vec3 magGauss() const { return glm::vec3(mag[0], mag[1], mag[2]) * 1e-4f; }
  bool operator==(const SensorReport&) const = default;
};

// dk2.md §3 units.
inline glm::vec3 accelMps2(const RawImuSample& s) {
  return glm::vec3(s.accel[0], s.accel[1], s.accel[2]) * 1e-4f;
}
inline glm::vec3 gyroRadPerS(const RawImuSample& s) {
  return glm::vec3(s.gyro[0], s.gyro[1], s.gyro[2]) * 1e-4f;
}

// Checks length, ID and the invariants of dk2.md §3; every outcome is counted in 'stats'.
Decoded<SensorReport> decodeSensorReport(std::span<const uint8_t> bytes,
                                         DecodeStats* stats = nullptr);
ReportBytes encodeSensorReport(const SensorReport& report);

}  // namespace photovr::hmd
