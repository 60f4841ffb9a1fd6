#include "hmd/synthetic.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <thread>

#include "hmd/feature_reports.h"
#include "hmd/fusion.h"
#include "hmd/sensor_stream.h"

namespace photovr::hmd {
namespace {

struct TrueSample {
  glm::dvec3 accel, gyro;  // SI, before quantisation
  glm::dquat q;            // orientation after the sample
};

class SampleSource {
 public:
  explicit SampleSource(const MotionScript& s) : s_(s), rng_(s.seed), q_(s.start) {}
  TrueSample next(double t) {
    const glm::dvec3 rate = rateAt(t);
    q_ = integrateGyro(q_, rate, kImuPeriod);
    const glm::dvec3 g = glm::conjugate(q_) * glm::dvec3(0.0, s_.gravity, 0.0);
    return {g + noise(s_.accelNoise), rate + s_.gyroBias + noise(s_.gyroNoise), q_};
  }

 private:
  glm::dvec3 rateAt(double t) const {
    for (const MotionSegment& m : s_.segments) {
      if (t < m.duration) return m.rate;
      t -= m.duration;
    }
    return glm::dvec3(0.0);
  }
  glm::dvec3 noise(double sigma) {
    if (sigma <= 0) return glm::dvec3(0.0);
    return {normal_(rng_) * sigma, normal_(rng_) * sigma, normal_(rng_) * sigma};
  }
  const MotionScript& s_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_;
  glm::dquat q_;
};

Packed21 quantise(const glm::dvec3& v) {  // to 1e-4 units (dk2.md §3)
  return {int32_t(std::lround(v.x * 1e4)), int32_t(std::lround(v.y * 1e4)),
          int32_t(std::lround(v.z * 1e4))};
}

RawImuSample slot(const std::vector<TrueSample>& s, size_t from, size_t to) {
  glm::dvec3 a(0.0), g(0.0);
  for (size_t i = from; i < to; ++i) a += s[i].accel, g += s[i].gyro;
  return {quantise(a / double(to - from)), quantise(g / double(to - from))};
}

SensorReport makeReport(const MotionScript& s, const std::vector<TrueSample>& batch,
                        uint64_t firstIndex) {
  SensorReport r;
  const size_t n = batch.size();
  r.numSamples = uint8_t(n);
  r.sampleCount = uint16_t(s.startSampleCount + firstIndex);
  r.temperature = s.temperature;
  r.timestampUs = uint32_t(s.startTimestampUs + (firstIndex + n - 1) * 1000);
  r.samples[0] = slot(batch, 0, n == 1 ? 1 : n - 1);
  if (n >= 2) r.samples[1] = slot(batch, n - 1, n);
  const glm::dvec3 mag = glm::conjugate(batch.back().q) * s.magneticField * 1e4;
  for (int i = 0; i < 3; ++i) r.mag[i] = int16_t(std::lround(mag[i]));
  return r;
}

bool isDropped(const MotionScript& s, double t) {
  return std::any_of(s.dropped.begin(), s.dropped.end(),
                     [t](const auto& w) { return t >= w.first && t < w.second; });
}

}  // namespace

SyntheticStream synthesize(const MotionScript& script) {
  double duration = 0.0;
  for (const MotionSegment& m : script.segments) duration += m.duration;
  const uint64_t total = uint64_t(std::llround(duration / kImuPeriod));
  const size_t perReport = size_t(std::clamp(script.samplesPerReport, 1, 254));
  SampleSource source(script);
  SyntheticStream out;
  std::vector<TrueSample> batch;
  for (uint64_t first = 0; first + perReport <= total; first += perReport) {
    batch.clear();
    for (size_t i = 0; i < perReport; ++i) batch.push_back(source.next((first + i) * kImuPeriod));
    const double t = (first + perReport - 1) * kImuPeriod;
    out.finalOrientation = batch.back().q;
    if (isDropped(script, t)) continue;
    out.reports.push_back(encodeSensorReport(makeReport(script, batch, first)));
    out.reportTimes.push_back(t);
    out.truth.push_back(batch.back().q);
  }
  out.duration = duration;
  return out;
}

std::vector<std::vector<uint8_t>> toVectors(const std::vector<ReportBytes>& reports) {
  std::vector<std::vector<uint8_t>> out;
  for (const ReportBytes& r : reports) out.emplace_back(r.begin(), r.end());
  return out;
}

SyntheticDevice::SyntheticDevice(const std::vector<ReportBytes>& reports)
    : SyntheticDevice(toVectors(reports), Options{}) {}

SyntheticDevice::SyntheticDevice(std::vector<std::vector<uint8_t>> reports, Options options)
    : reports_(std::move(reports)), options_(options) {
  for (auto bytes : {encode(ConfigReport{}), encode(RangeReport{}), encode(DisplayInfoReport{}),
                     encode(TrackingLedsReport{}), encode(KeepAliveReport{})})
    features_[bytes[0]] = bytes;
  if (options_.hasLensReport)
    features_[LensDistortionReport::kId] = encode(LensDistortionReport::firmwareDefault());
}

int SyntheticDevice::readReport(std::span<uint8_t> buffer, int timeoutMs) {
  std::unique_lock lock(mutex_);
  if (next_ >= reports_.size()) {
    if (options_.vanishAtEnd) return -1;
    lock.unlock();
    std::this_thread::sleep_for(std::chrono::milliseconds(timeoutMs));
    return 0;
  }
  const std::vector<uint8_t>& r = reports_[next_++];
  const size_t n = std::min(buffer.size(), r.size());
  std::copy_n(r.begin(), n, buffer.begin());
  return int(n);
}

int SyntheticDevice::getFeature(std::span<uint8_t> buffer) {
  std::lock_guard lock(mutex_);
  if (buffer.empty()) return -1;
  const auto it = features_.find(buffer[0]);
  if (it == features_.end()) return -1;
  const size_t n = std::min(buffer.size(), it->second.size());
  std::copy_n(it->second.begin(), n, buffer.begin());
  return int(n);
}

bool SyntheticDevice::setFeature(std::span<const uint8_t> report) {
  std::lock_guard lock(mutex_);
  if (report.empty() || options_.refuseSets) return false;
  sets_.emplace_back(report.begin(), report.end());
  features_[report[0]] = sets_.back();
  return true;
}

std::vector<std::vector<uint8_t>> SyntheticDevice::sets() const {
  std::lock_guard lock(mutex_);
  return sets_;
}

}  // namespace photovr::hmd
