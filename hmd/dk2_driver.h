// The DK2 driver above the HmdDevice seam: start-up sequence, keep-alive timer, a reader
// thread decoding sensor reports into a sample queue, clean shutdown (dk2.md §2-§3).
#pragma once

#include <atomic>
#include <chrono>
#include <deque>
#include <functional>
#include <iosfwd>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "hmd/feature_reports.h"
#include "hmd/hmd_device.h"
#include "hmd/sensor_stream.h"

namespace photovr::hmd {

// What the headset said about itself at start-up; documented defaults where it did not.
struct Dk2DeviceInfo {
  ConfigReport config;
  RangeReport range;
  DisplayInfoReport display;
  std::optional<LensDistortionReport> lens;  // absent on firmware without 0x16
  TrackingLedsReport leds;
};

// Seconds on a monotonic host clock (steady_clock).
double hostSeconds();

struct Dk2DriverOptions {
  // dk2.md §2: streaming stops 'interval' ms after the last feature SET; we ask for 10 s
  // and re-send every ~3 s, so two lost keep-alives in a row still keep it streaming.
  std::chrono::milliseconds keepAlivePeriod{3000};
  int readTimeoutMs = 50;  // bounds how long stop() waits for the reader
  bool trackingLeds = true;
  size_t maxQueuedSamples = 1 << 14;  // ~16 s at 1 kHz; older samples are dropped
  std::function<double()> hostClock = hostSeconds;
  std::ostream* log = nullptr;  // one line when the device is lost; nullptr = std::cerr
};

class Dk2Driver {
 public:
  explicit Dk2Driver(std::unique_ptr<HmdDevice> device, Dk2DriverOptions options = {});
  ~Dk2Driver();
  Dk2Driver(const Dk2Driver&) = delete;
  Dk2Driver& operator=(const Dk2Driver&) = delete;

  // Start-up sequence (dk2.md §2) then the reader thread. Throws InputError when the
  // device refuses the keep-alive (nothing would stream).
  void start();
  // Stops the reader and turns the tracking LEDs off (unless the device is gone).
  void stop();

  std::vector<ImuSample> takeSamples();  // everything decoded since the last call
  bool lost() const { return lost_; }
  DecodeStats sensorStats() const;
  const DecodeStats& featureStats() const { return featureStats_; }
  const Dk2DeviceInfo& info() const { return info_; }
  uint64_t keepAlivesSent() const { return keepAlives_; }
  uint64_t queueOverflows() const;
  std::string name() const { return device_->name(); }

 private:
  template <class R>
  std::optional<R> getFeature(Decoded<R> (*decode)(std::span<const uint8_t>, DecodeStats*));
  bool sendKeepAlive();
  void configure();
  void readerLoop();
  void deliver(std::span<const uint8_t> report);
  void markLost(const char* why);

  std::unique_ptr<HmdDevice> device_;
  Dk2DriverOptions options_;
  Dk2DeviceInfo info_;
  DecodeStats featureStats_;
  SensorStream stream_;
  std::deque<ImuSample> queue_;
  uint64_t overflows_ = 0;
  mutable std::mutex mutex_;  // guards stream_ stats, queue_, overflows_
  std::thread reader_;
  std::atomic<bool> running_{false}, lost_{false};
  std::atomic<uint64_t> keepAlives_{0};
};

}  // namespace photovr::hmd
