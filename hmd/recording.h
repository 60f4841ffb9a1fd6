// Raw HID traffic on disk: a recorder that wraps any HmdDevice and writes what passes
// through it, and a replay device that plays such a file back through the same driver.
//
// File format (little-endian, version 1):
//   8 bytes   magic "PVRHID01"
//   records until end of file, each:
//     u8      kind: 1 = input report read, 2 = feature report GET reply, 3 = feature SET sent
//     u64     host time, nanoseconds since the recording started (steady clock)
//     u16     length n, 1..kMaxRecordBytes
//     n bytes the report as hidapi returned or sent it, report ID first
// A truncated last record or any other malformation is an InputError naming the file,
// the record number and its byte offset.
#pragma once

#include <cstdint>
#include <fstream>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "hmd/hmd_device.h"

namespace photovr::hmd {

constexpr char kRecordingMagic[9] = "PVRHID01";
constexpr size_t kMaxRecordBytes = 1024;

struct HidRecord {
  enum Kind : uint8_t { Input = 1, FeatureGet = 2, FeatureSet = 3 };
  Kind kind = Input;
  uint64_t hostNs = 0;
  std::vector<uint8_t> bytes;
  bool operator==(const HidRecord&) const = default;
};

std::vector<HidRecord> readRecording(const std::string& path);

class RecordingWriter {
 public:
  explicit RecordingWriter(const std::string& path);  // throws InputError
  void write(const HidRecord& record);
  void flush();

 private:
  std::string path_;
  std::ofstream out_;
};

// Passes every call through to 'inner' and records it, stamped with the host time.
class RecordingDevice final : public HmdDevice {
 public:
  RecordingDevice(std::unique_ptr<HmdDevice> inner, const std::string& path);
  int readReport(std::span<uint8_t> buffer, int timeoutMs) override;
  int getFeature(std::span<uint8_t> buffer) override;
  bool setFeature(std::span<const uint8_t> report) override;
  std::string name() const override { return inner_->name() + " (recording)"; }

 private:
  void record(HidRecord::Kind kind, std::span<const uint8_t> bytes);
  std::unique_ptr<HmdDevice> inner_;
  RecordingWriter writer_;
  std::mutex mutex_;
  double start_;
};

// Plays a recording: input reports in order (as fast as they are read, or at their
// recorded pace), feature GETs answered from the recorded replies with the same ID in
// order (the last one repeats), SETs accepted and ignored. -1 after the last input report.
class ReplayDevice final : public HmdDevice {
 public:
  enum class Pacing { AsFastAsRead, Recorded };
  explicit ReplayDevice(const std::string& path, Pacing pacing = Pacing::AsFastAsRead);
  int readReport(std::span<uint8_t> buffer, int timeoutMs) override;
  int getFeature(std::span<uint8_t> buffer) override;
  bool setFeature(std::span<const uint8_t>) override { return true; }
  std::string name() const override { return "replay " + path_; }

 private:
  std::string path_;
  Pacing pacing_;
  std::vector<HidRecord> records_;
  size_t nextInput_ = 0;
  std::vector<size_t> nextGet_;  // per report ID: index into records_ to search from
  double start_ = -1.0;
};

}  // namespace photovr::hmd
