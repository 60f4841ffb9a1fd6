// Turns a sequence of sensor reports into timed IMU samples: timestamp unwrap, per-sample
// dt with the averaged-sample semantics, dropped-sample accounting (dk2.md §3).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "hmd/decode_stats.h"
#include "hmd/sensor_report.h"

namespace photovr::hmd {

// One IMU reading in headset axes (X right, Y up, Z toward the wearer; dk2.md §3).
struct ImuSample {
  double time = 0.0;      // device clock, seconds, unwrapped
  double dt = 0.0;        // seconds this reading stands for (> 1 ms for an averaged slot)
  double hostTime = 0.0;  // host clock when its report arrived (caller's epoch), seconds
  glm::vec3 accel{0.0f};  // m/s^2
  glm::vec3 gyro{0.0f};   // rad/s
  glm::vec3 mag{0.0f};    // gauss
  float temperatureC = 0.0f;
};

// The DK2 samples at 1000 Hz (dk2.md §1, §3).
constexpr double kImuPeriod = 1e-3;
// A gap up to this long is bridged by holding the first slot's rate (the usual lost USB
// packet costs a few ms); a longer one restarts the timing without integrating across it,
// since a held rate over 100+ ms would be a guess (tilt correction repairs pitch and roll).
constexpr double kMaxBridgedGap = 0.1;

class SensorStream {
 public:
  // Decodes one HID input report; returns its samples oldest first, or none when the
  // report is rejected (counted in stats()).
  std::vector<ImuSample> push(std::span<const uint8_t> bytes, double hostTime = 0.0);
  std::vector<ImuSample> push(const SensorReport& report, double hostTime = 0.0);
  const DecodeStats& stats() const { return stats_; }
  double time() const { return timeUs_ * 1e-6; }

 private:
  double firstSlotDt(const SensorReport& r, uint32_t deltaUs) const;
  void countDropped(const SensorReport& r);

  DecodeStats stats_;
  bool started_ = false;
  uint32_t lastRawUs_ = 0;
  uint16_t lastSampleCount_ = 0;
  uint64_t timeUs_ = 0;  // unwrapped
  uint16_t nextSampleCount_ = 0;
};

}  // namespace photovr::hmd
