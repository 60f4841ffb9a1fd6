// The DK2 feature reports the driver uses (dk2.md §2), as raw integer fields so that
// encode/decode round-trip byte for byte. Sizes include the report-ID byte.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "hmd/decode_stats.h"

namespace photovr::hmd {

struct ConfigReport {  // 0x02
  static constexpr uint8_t kId = 0x02;
  static constexpr size_t kSize = 7;
  // Flag bits (dk2.md §2).
  static constexpr uint8_t kRaw = 0x01, kCalibTest = 0x02, kUseCalibration = 0x04,
                           kAutoCalibration = 0x08, kMotionKeepAlive = 0x10,
                           kCommandKeepAlive = 0x20, kSensorCoordinates = 0x40,
                           kOverridePower = 0x80;
  uint16_t commandId = 0;
  uint8_t flags = 0x2C;        // firmware default
  uint8_t packetInterval = 0;  // report rate 1000 / (n + 1) Hz
  uint16_t sampleRate = 1000;  // read-only
  bool operator==(const ConfigReport&) const = default;
};

struct RangeReport {  // 0x04
  static constexpr uint8_t kId = 0x04;
  static constexpr size_t kSize = 8;
  uint16_t commandId = 0;
  uint8_t accelG = 4;
  uint16_t gyroDegPerS = 2000;
  uint16_t magMilliGauss = 4000;
  bool operator==(const RangeReport&) const = default;
};

struct DisplayInfoReport {  // 0x09; lengths in micrometres, DK2 defaults (dk2.md §2)
  static constexpr uint8_t kId = 0x09;
  static constexpr size_t kSize = 56;
  uint16_t commandId = 0;
  uint8_t distortionType = 1;
  uint16_t hResolution = 1920, vResolution = 1080;
  uint32_t widthUm = 125760, heightUm = 70740, verticalCentreUm = 35370;
  uint32_t lensSeparationUm = 63500, lensDistanceLeftUm = 39620, lensDistanceRightUm = 39620;
  std::array<float, 6> distortion{};
  bool operator==(const DisplayInfoReport&) const = default;
};

struct TrackingLedsReport {  // 0x0C
  static constexpr uint8_t kId = 0x0C;
  static constexpr size_t kSize = 13;
  static constexpr uint16_t kEnable = 0x01, kAutoIncrement = 0x02, kCarrier85kHz = 0x04,
                            kSyncIn = 0x08, kVsyncLock = 0x10, kCustomPattern = 0x20;
  uint16_t commandId = 0;
  uint8_t pattern = 0;
  uint16_t flags = 0;
  uint16_t exposureUs = 0, periodUs = 0, vsyncOffset = 0;
  uint8_t dutyCycle = 0;  // 128 = 50 %
  // dk2.md §2 start-up: blinking pattern, 350 us exposure, 60 Hz period, duty 0x7F.
  static TrackingLedsReport blinking() { return {0, 0, 0x07, 350, 16666, 0, 0x7F}; }
  bool operator==(const TrackingLedsReport&) const = default;
};

struct KeepAliveReport {  // 0x11
  static constexpr uint8_t kId = 0x11;
  static constexpr size_t kSize = 6;
  uint16_t commandId = 0;
  uint8_t reportId = 0x0B;      // keep the DK2 sensor report streaming
  uint16_t intervalMs = 10000;  // dk2.md §2: 11 00 00 0B 10 27
  bool operator==(const KeepAliveReport&) const = default;
};

struct LensDistortionReport {  // 0x16, fixed point as stored by the firmware
  static constexpr uint8_t kId = 0x16;
  static constexpr size_t kSize = 64;
  static constexpr uint16_t kCatmullRom10 = 1;
  uint16_t commandId = 0;
  uint8_t numEntries = 1, index = 0, bitmask = 0;
  uint16_t lensType = 0;
  uint16_t version = kCatmullRom10;
  uint16_t eyeReliefUm = 0;
  std::array<uint16_t, 11> k{};      // K = raw / 2^14
  uint16_t maxR = 0;                 // raw / 2^14 (same fixed point as K)
  uint16_t metresPerTanAngle = 0;    // raw / 2^19
  std::array<uint16_t, 4> chroma{};  // (raw - 0x8000) / 2^19
  // The firmware's default: the DK2 K set, MaxR 1, 0.036 m per tan-angle and the 18 mm
  // chromatic terms stored at 17000 um (dk2.md §6).
  static LensDistortionReport firmwareDefault();
  bool operator==(const LensDistortionReport&) const = default;
};

std::vector<uint8_t> encode(const ConfigReport& r);
std::vector<uint8_t> encode(const RangeReport& r);
std::vector<uint8_t> encode(const DisplayInfoReport& r);
std::vector<uint8_t> encode(const TrackingLedsReport& r);
std::vector<uint8_t> encode(const KeepAliveReport& r);
std::vector<uint8_t> encode(const LensDistortionReport& r);

// Each checks the ID, the length (>= kSize; hidraw may return a padded buffer, the bytes
// past the layout are ignored) and the field ranges dk2.md §2 gives.
Decoded<ConfigReport> decodeConfig(std::span<const uint8_t> b, DecodeStats* stats = nullptr);
Decoded<RangeReport> decodeRange(std::span<const uint8_t> b, DecodeStats* stats = nullptr);
Decoded<DisplayInfoReport> decodeDisplayInfo(std::span<const uint8_t> b,
                                             DecodeStats* stats = nullptr);
Decoded<TrackingLedsReport> decodeTrackingLeds(std::span<const uint8_t> b,
                                               DecodeStats* stats = nullptr);
Decoded<KeepAliveReport> decodeKeepAlive(std::span<const uint8_t> b, DecodeStats* stats = nullptr);
Decoded<LensDistortionReport> decodeLensDistortion(std::span<const uint8_t> b,
                                                   DecodeStats* stats = nullptr);

}  // namespace photovr::hmd
