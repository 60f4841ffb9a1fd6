// Byte-exact DK2 sensor reports from a scripted motion, and a device serving them with the
// firmware's default feature reports — the headset replaced, not skipped (STYLE.md 11).
#pragma once

#include <cstdint>
#include <map>
#include <mutex>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "hmd/hmd_device.h"
#include "hmd/sensor_report.h"

namespace photovr::hmd {

struct MotionSegment {
  double duration = 1.0;  // seconds
  glm::dvec3 rate{0.0};   // body-frame angular rate, rad/s, constant over the segment
};

struct MotionScript {
  glm::dquat start{1.0, 0.0, 0.0, 0.0};  // body -> world at t = 0 (tilt, heading)
  std::vector<MotionSegment> segments;
  glm::dvec3 gyroBias{0.0};  // rad/s, added to every gyro reading
  double gyroNoise = 0.0;    // rad/s, standard deviation per sample and axis
  double accelNoise = 0.0;   // m/s^2, likewise
  uint64_t seed = 1;         // noise is reproducible
  double gravity = 9.81;
  glm::dvec3 magneticField{0.2, -0.4, 0.1};  // gauss, world frame
  int16_t temperature = 3500;                // 0.01 C
  uint32_t startTimestampUs = 0;             // set near 2^32 to cross the timestamp wrap
  uint16_t startSampleCount = 0;
  int samplesPerReport = 1;  // 1-254; > 2 exercises the averaged slot (dk2.md §3)
  std::vector<std::pair<double, double>> dropped;  // [from, to) s: reports lost in transit
};

struct SyntheticStream {
  std::vector<ReportBytes> reports;
  std::vector<double> reportTimes;  // seconds since start of each report's newest sample
  std::vector<glm::dquat> truth;    // orientation after each report's newest sample
  glm::dquat finalOrientation{1.0, 0.0, 0.0, 0.0};
  double duration = 0.0;
};

// The true orientation integrates each 1 ms sample's rate exactly; each sample's accel is
// gravity in the body frame (no linear acceleration), readings quantised to 1e-4 units.
SyntheticStream synthesize(const MotionScript& script);

// A synthetic headset behind the HmdDevice interface. Feature GETs are answered from a
// table holding the firmware defaults (dk2.md §2, §8); SETs are recorded and update it.
class SyntheticDevice final : public HmdDevice {
 public:
  struct Options {
    bool vanishAtEnd = true;  // -1 after the last report; otherwise idle (timeouts)
    bool hasLensReport = true;
    bool refuseSets = false;
  };
  explicit SyntheticDevice(std::vector<std::vector<uint8_t>> reports, Options options);
  explicit SyntheticDevice(const std::vector<ReportBytes>& reports);
  int readReport(std::span<uint8_t> buffer, int timeoutMs) override;
  int getFeature(std::span<uint8_t> buffer) override;
  bool setFeature(std::span<const uint8_t> report) override;
  std::string name() const override { return "synthetic DK2"; }
  std::vector<std::vector<uint8_t>> sets() const;  // every SET so far, in order

 private:
  std::vector<std::vector<uint8_t>> reports_;
  Options options_;
  size_t next_ = 0;
  std::map<uint8_t, std::vector<uint8_t>> features_;
  std::vector<std::vector<uint8_t>> sets_;
  mutable std::mutex mutex_;
};

std::vector<std::vector<uint8_t>> toVectors(const std::vector<ReportBytes>& reports);

}  // namespace photovr::hmd
