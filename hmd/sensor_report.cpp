#include "hmd/sensor_report.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "hmd/bytes.h"

namespace photovr::hmd {
namespace {

int32_t signExtend21(uint32_t v) {
  return int32_t(v << 11) >> 11;
}

// The widest gyro range is 2000 deg/s (dk2.md §2, 0x04); 10 % above it is no longer a
// reading, it is a corrupted word.
constexpr double kMaxGyroRaw = 2000.0 * std::numbers::pi / 180.0 * 1e4 * 1.1;
// Operating range of the electronics; a reading outside it is not a temperature.
constexpr int kMinTemperature = -4000, kMaxTemperature = 12500;  // 0.01 C

RawImuSample readSample(const uint8_t* p) {
  return {unpack21(p), unpack21(p + 8)};
}

void writeSample(const RawImuSample& s, uint8_t* p) {
  pack21(s.accel, p);
  pack21(s.gyro, p + 8);
}

bool gyroPlausible(const RawImuSample& s) {
  return std::all_of(s.gyro.begin(), s.gyro.end(),
                     [](int32_t g) { return std::abs(double(g)) <= kMaxGyroRaw; });
}

SensorReport readFields(const uint8_t* b) {
  SensorReport r;
  r.commandId = le16(b + 1);
  r.numSamples = b[3];
  r.sampleCount = le16(b + 4);
  r.temperature = int16_t(le16(b + 6));
  r.timestampUs = le32(b + 8);
  r.samples = {readSample(b + 12), readSample(b + 28)};
  for (int i = 0; i < 3; ++i) r.mag[i] = int16_t(le16(b + 44 + 2 * i));
  r.frameCount = le16(b + 50);
  r.frameTimestamp = le32(b + 52);
  r.frameId = b[56];
  r.ledPhase = b[57];
  r.exposureCount = le16(b + 58);
  r.exposureTimestamp = le32(b + 60);
  return r;
}

}  // namespace

Packed21 unpack21(const uint8_t* b) {
  return {signExtend21((uint32_t(b[0]) << 13) | (uint32_t(b[1]) << 5) | (b[2] >> 3)),
          signExtend21((uint32_t(b[2] & 7) << 18) | (uint32_t(b[3]) << 10) | (uint32_t(b[4]) << 2) |
                       (b[5] >> 6)),
          signExtend21((uint32_t(b[5] & 0x3F) << 15) | (uint32_t(b[6]) << 7) | (b[7] >> 1))};
}

void pack21(const Packed21& v, uint8_t* b) {
  // x in bits 63-43, y in 42-22, z in 21-1 of a big-endian word; bit 0 unused (dk2.md §3).
  uint64_t word = 0;
  for (int i = 0; i < 3; ++i) {
    const uint32_t field = uint32_t(std::clamp(v[i], kPacked21Min, kPacked21Max)) & 0x1FFFFF;
    word |= uint64_t(field) << (43 - 21 * i);
  }
  for (int i = 0; i < 8; ++i) b[i] = uint8_t(word >> (56 - 8 * i));
}

Decoded<SensorReport> decodeSensorReport(std::span<const uint8_t> bytes, DecodeStats* stats) {
  if (bytes.empty()) return rejected<SensorReport>(Reject::Empty, stats);
  if (bytes[0] != kSensorReportId) return rejected<SensorReport>(Reject::WrongId, stats);
  if (bytes.size() < kSensorReportSize) return rejected<SensorReport>(Reject::Short, stats);
  const SensorReport r = readFields(bytes.data());
  if (r.numSamples == 0) return rejected<SensorReport>(Reject::NoSamples, stats);
  if (r.numSamples == 1 &&
      std::any_of(bytes.begin() + 28, bytes.begin() + 44, [](uint8_t b) { return b != 0; }))
    return rejected<SensorReport>(Reject::UnusedSlotNotZero, stats);
  const bool plausible = r.temperature >= kMinTemperature && r.temperature <= kMaxTemperature &&
                         gyroPlausible(r.samples[0]) && gyroPlausible(r.samples[1]);
  if (!plausible) return rejected<SensorReport>(Reject::OutOfRange, stats);
  return accepted(r, stats);
}

ReportBytes encodeSensorReport(const SensorReport& r) {
  ReportBytes b{};
  b[0] = kSensorReportId;
  putLe16(&b[1], r.commandId);
  b[3] = r.numSamples;
  putLe16(&b[4], r.sampleCount);
  putLe16(&b[6], uint16_t(r.temperature));
  putLe32(&b[8], r.timestampUs);
  writeSample(r.samples[0], &b[12]);
  if (r.numSamples != 1) writeSample(r.samples[1], &b[28]);
  for (int i = 0; i < 3; ++i) putLe16(&b[44 + 2 * i], uint16_t(r.mag[i]));
  putLe16(&b[50], r.frameCount);
  putLe32(&b[52], r.frameTimestamp);
  b[56] = r.frameId;
  b[57] = r.ledPhase;
  putLe16(&b[58], r.exposureCount);
  putLe32(&b[60], r.exposureTimestamp);
  return b;
}

}  // namespace photovr::hmd
