#include "hmd/sensor_stream.h"

#include <algorithm>

namespace photovr::hmd {
namespace {

ImuSample toSample(const SensorReport& r, int slot, double time, double dt, double hostTime) {
  ImuSample s;
  s.time = time;
  s.dt = dt;
  s.hostTime = hostTime;
  s.accel = accelMps2(r.samples[slot]);
  s.gyro = gyroRadPerS(r.samples[slot]);
  s.mag = r.magGauss();
  s.temperatureC = r.temperatureC();
  return s;
}

}  // namespace

std::vector<ImuSample> SensorStream::push(std::span<const uint8_t> bytes, double hostTime) {
  DecodeStats decode;
  const Decoded<SensorReport> r = decodeSensorReport(bytes, &decode);
  if (!r) {
    stats_.count(r.reason);
    return {};
  }
  return push(*r, hostTime);
}

double SensorStream::firstSlotDt(const SensorReport& r, uint32_t deltaUs) const {
  // Slot 0 stands for every sample but the newest; slot 1 (when present) for the newest.
  const int laterSlots = r.slotsUsed() - 1;
  const double nominal = std::max(1, r.numSamples - laterSlots) * kImuPeriod;
  if (!started_ || deltaUs * 1e-6 > kMaxBridgedGap) return nominal;
  return std::max(0.0, deltaUs * 1e-6 - laterSlots * kImuPeriod);
}

void SensorStream::countDropped(const SensorReport& r) {
  // SampleCount numbers the first sample of a report (dk2.md §3); a jump means samples
  // were lost. A jump of half the 16-bit range or more is a restart, not a loss.
  const uint16_t missing = uint16_t(r.sampleCount - nextSampleCount_);
  if (missing > 0 && missing < 0x8000) stats_.droppedSamples += missing;
}

std::vector<ImuSample> SensorStream::push(const SensorReport& r, double hostTime) {
  // Modular difference: forward steps below 2^31 us are progress (including the 2^32 wrap,
  // dk2.md §3); anything else is an old or corrupted report, not a 71-minute jump.
  const uint32_t delta = r.timestampUs - lastRawUs_;
  if (started_ && delta == 0 && r.sampleCount == lastSampleCount_) {
    stats_.count(Reject::Duplicate);
    return {};
  }
  if (started_ && (delta == 0 || delta >= 0x80000000u)) {
    stats_.count(Reject::TimestampBackwards);
    return {};
  }
  stats_.count(Reject::None);
  if (started_) countDropped(r);
  if (started_ && delta * 1e-6 > kMaxBridgedGap) ++stats_.resyncs;
  const double dt0 = firstSlotDt(r, delta);
  timeUs_ = started_ ? timeUs_ + delta : r.timestampUs;
  started_ = true;
  lastRawUs_ = r.timestampUs;
  lastSampleCount_ = r.sampleCount;
  nextSampleCount_ = uint16_t(r.sampleCount + r.numSamples);

  const double t = time();
  if (r.slotsUsed() == 1) return {toSample(r, 0, t, dt0, hostTime)};
  return {toSample(r, 0, t - kImuPeriod, dt0, hostTime), toSample(r, 1, t, kImuPeriod, hostTime)};
}

}  // namespace photovr::hmd
