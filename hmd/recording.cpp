#include "hmd/recording.h"

#include <algorithm>
#include <cstring>
#include <iterator>
#include <thread>

#include "core/error.h"
#include "core/files.h"
#include "hmd/bytes.h"
#include "hmd/dk2_driver.h"

namespace photovr::hmd {
namespace {

constexpr size_t kRecordHeader = 1 + 8 + 2;

std::vector<uint8_t> slurp(const std::string& path) {
  const std::string bytes = readRegularFile(path, "HID recording");
  return {bytes.begin(), bytes.end()};
}

HidRecord parseRecord(const std::string& path, const std::vector<uint8_t>& data, size_t& at,
                      size_t index) {
  const std::string where = "record " + std::to_string(index) + " at byte " + std::to_string(at);
  if (data.size() - at < kRecordHeader) throw InputError(path, where + ": truncated header");
  HidRecord r;
  const uint8_t kind = data[at];
  if (kind < HidRecord::Input || kind > HidRecord::FeatureSet)
    throw InputError(path, where + ": unknown kind " + std::to_string(kind) + " (expected 1-3)");
  r.kind = HidRecord::Kind(kind);
  r.hostNs = uint64_t(le32(&data[at + 1])) | (uint64_t(le32(&data[at + 5])) << 32);
  const size_t n = le16(&data[at + 9]);
  if (n == 0 || n > kMaxRecordBytes)
    throw InputError(path, where + ": length " + std::to_string(n) + " (expected 1-1024)");
  at += kRecordHeader;
  if (data.size() - at < n) throw InputError(path, where + ": truncated report");
  r.bytes.assign(data.begin() + at, data.begin() + at + n);
  at += n;
  return r;
}

}  // namespace

std::vector<HidRecord> readRecording(const std::string& path) {
  const std::vector<uint8_t> data = slurp(path);
  if (data.size() < 8 || std::memcmp(data.data(), kRecordingMagic, 8) != 0)
    throw InputError(path, "not a photovr HID recording (expected magic PVRHID01)");
  std::vector<HidRecord> records;
  for (size_t at = 8; at < data.size();)
    records.push_back(parseRecord(path, data, at, records.size()));
  return records;
}

RecordingWriter::RecordingWriter(const std::string& path)
    : path_(path), out_(path, std::ios::binary | std::ios::trunc) {
  if (!out_) throw InputError(path, "cannot create the HID recording");
  out_.write(kRecordingMagic, 8);
}

void RecordingWriter::write(const HidRecord& r) {
  if (r.bytes.empty() || r.bytes.size() > kMaxRecordBytes)
    throw InputError(path_, "cannot record a report of " + std::to_string(r.bytes.size()) +
                                " bytes (expected 1-1024)");
  uint8_t header[kRecordHeader];
  header[0] = r.kind;
  putLe32(header + 1, uint32_t(r.hostNs));
  putLe32(header + 5, uint32_t(r.hostNs >> 32));
  putLe16(header + 9, uint16_t(r.bytes.size()));
  out_.write(reinterpret_cast<const char*>(header), kRecordHeader);
  out_.write(reinterpret_cast<const char*>(r.bytes.data()), std::streamsize(r.bytes.size()));
  if (!out_) throw InputError(path_, "write failed");
}

void RecordingWriter::flush() {
  out_.flush();
}

RecordingDevice::RecordingDevice(std::unique_ptr<HmdDevice> inner, const std::string& path)
    : inner_(std::move(inner)), writer_(path), start_(hostSeconds()) {}

void RecordingDevice::record(HidRecord::Kind kind, std::span<const uint8_t> bytes) {
  const double t = std::max(0.0, hostSeconds() - start_);
  std::lock_guard lock(mutex_);
  writer_.write({kind, uint64_t(t * 1e9), {bytes.begin(), bytes.end()}});
  writer_.flush();
}

int RecordingDevice::readReport(std::span<uint8_t> buffer, int timeoutMs) {
  const int n = inner_->readReport(buffer, timeoutMs);
  if (n > 0) record(HidRecord::Input, buffer.first(std::min<size_t>(n, buffer.size())));
  return n;
}

int RecordingDevice::getFeature(std::span<uint8_t> buffer) {
  const int n = inner_->getFeature(buffer);
  if (n > 0) record(HidRecord::FeatureGet, buffer.first(std::min<size_t>(n, buffer.size())));
  return n;
}

bool RecordingDevice::setFeature(std::span<const uint8_t> report) {
  if (!report.empty()) record(HidRecord::FeatureSet, report);
  return inner_->setFeature(report);
}

ReplayDevice::ReplayDevice(const std::string& path, Pacing pacing)
    : path_(path), pacing_(pacing), records_(readRecording(path)), nextGet_(256, 0) {}

int ReplayDevice::readReport(std::span<uint8_t> buffer, int /*timeoutMs*/) {
  while (nextInput_ < records_.size() && records_[nextInput_].kind != HidRecord::Input)
    ++nextInput_;
  if (nextInput_ >= records_.size()) return -1;
  const HidRecord& r = records_[nextInput_++];
  if (pacing_ == Pacing::Recorded) {
    if (start_ < 0) start_ = hostSeconds() - r.hostNs * 1e-9;
    const double wait = start_ + r.hostNs * 1e-9 - hostSeconds();
    if (wait > 0) std::this_thread::sleep_for(std::chrono::duration<double>(wait));
  }
  const size_t n = std::min(buffer.size(), r.bytes.size());
  std::copy_n(r.bytes.begin(), n, buffer.begin());
  return int(n);
}

int ReplayDevice::getFeature(std::span<uint8_t> buffer) {
  if (buffer.empty()) return -1;
  const uint8_t id = buffer[0];
  auto matches = [&](const HidRecord& r) {
    return r.kind == HidRecord::FeatureGet && r.bytes[0] == id;
  };
  auto it = std::find_if(records_.begin() + nextGet_[id], records_.end(), matches);
  if (it == records_.end()) {  // repeat the last reply with this ID, if any
    auto last = std::find_if(records_.rbegin(), records_.rend(), matches);
    if (last == records_.rend()) return -1;
    it = last.base() - 1;
  }
  nextGet_[id] = size_t(it - records_.begin()) + 1;
  const size_t n = std::min(buffer.size(), it->bytes.size());
  std::copy_n(it->bytes.begin(), n, buffer.begin());
  return int(n);
}

}  // namespace photovr::hmd
