#include "hmd/dk2_driver.h"

#include <iostream>

#include "core/error.h"

namespace photovr::hmd {

double hostSeconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

Dk2Driver::Dk2Driver(std::unique_ptr<HmdDevice> device, Dk2DriverOptions options)
    : device_(std::move(device)), options_(std::move(options)) {}

Dk2Driver::~Dk2Driver() {
  stop();
}

template <class R>
std::optional<R> Dk2Driver::getFeature(Decoded<R> (*decode)(std::span<const uint8_t>,
                                                            DecodeStats*)) {
  std::vector<uint8_t> buffer(R::kSize, 0);
  buffer[0] = R::kId;
  const int n = device_->getFeature(buffer);
  if (n <= 0) return std::nullopt;
  const Decoded<R> r =
      decode(std::span(buffer).first(std::min<size_t>(n, buffer.size())), &featureStats_);
  return r.value;
}

bool Dk2Driver::sendKeepAlive() {
  ++keepAlives_;
  return device_->setFeature(encode(KeepAliveReport{}));
}

void Dk2Driver::configure() {
  // dk2.md §2 start-up: read range, display and lens; get-modify-set the config for
  // 1000 Hz with command keep-alive (the default 0x2C already has it); LEDs on.
  info_.range = getFeature(decodeRange).value_or(RangeReport{});
  info_.display = getFeature(decodeDisplayInfo).value_or(DisplayInfoReport{});
  info_.lens = getFeature(decodeLensDistortion);
  ConfigReport config = getFeature(decodeConfig).value_or(ConfigReport{});
  config.packetInterval = 0;
  config.flags |= ConfigReport::kCommandKeepAlive;
  device_->setFeature(encode(config));
  info_.config = config;
  if (!options_.trackingLeds) return;
  info_.leds = TrackingLedsReport::blinking();
  device_->setFeature(encode(info_.leds));
}

void Dk2Driver::start() {
  if (running_) return;
  if (!sendKeepAlive())
    throw InputError(device_->name(), "refused the keep-alive feature report 0x11");
  configure();
  lost_ = false;
  running_ = true;
  reader_ = std::thread([this] { readerLoop(); });
}

void Dk2Driver::stop() {
  if (!reader_.joinable()) return;
  running_ = false;
  reader_.join();
  if (lost_ || !options_.trackingLeds) return;
  // dk2.md §2: LEDs off = get 0x0C, clear bit 0, set.
  TrackingLedsReport leds = getFeature(decodeTrackingLeds).value_or(info_.leds);
  leds.flags &= ~TrackingLedsReport::kEnable;
  device_->setFeature(encode(leds));
}

void Dk2Driver::markLost(const char* why) {
  std::ostream& log = options_.log ? *options_.log : std::cerr;
  log << "hmd: " << device_->name() << ": " << why << "; holding the last pose\n";
  running_ = false;
  lost_ = true;  // last: whoever sees it may read the log
}

void Dk2Driver::deliver(std::span<const uint8_t> report) {
  const double now = options_.hostClock();
  std::lock_guard lock(mutex_);
  for (const ImuSample& s : stream_.push(report, now)) {
    if (queue_.size() >= options_.maxQueuedSamples) {
      queue_.pop_front();
      ++overflows_;
    }
    queue_.push_back(s);
  }
}

void Dk2Driver::readerLoop() {
  std::vector<uint8_t> buffer(kSensorReportSize);
  auto lastKeepAlive = std::chrono::steady_clock::now();
  while (running_) {
    if (std::chrono::steady_clock::now() - lastKeepAlive >= options_.keepAlivePeriod) {
      lastKeepAlive = std::chrono::steady_clock::now();
      if (!sendKeepAlive()) return markLost("keep-alive refused (device lost)");
    }
    const int n = device_->readReport(buffer, options_.readTimeoutMs);
    if (n < 0) return markLost("no more sensor reports (device lost or recording ended)");
    if (n > 0) deliver(std::span(buffer).first(std::min<size_t>(n, buffer.size())));
  }
}

std::vector<ImuSample> Dk2Driver::takeSamples() {
  std::lock_guard lock(mutex_);
  std::vector<ImuSample> out(queue_.begin(), queue_.end());
  queue_.clear();
  return out;
}

DecodeStats Dk2Driver::sensorStats() const {
  std::lock_guard lock(mutex_);
  return stream_.stats();
}

uint64_t Dk2Driver::queueOverflows() const {
  std::lock_guard lock(mutex_);
  return overflows_;
}

}  // namespace photovr::hmd
