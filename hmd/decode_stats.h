// Why a HID report was not trusted, and how often (issue 6: every malformed, short or
// unknown report is counted and skipped).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace photovr::hmd {

enum class Reject : uint8_t {
  None,
  Empty,               // zero bytes
  WrongId,             // byte 0 is not the expected report ID
  Short,               // fewer bytes than the layout (dk2.md §2-§3)
  NoSamples,           // sensor report with NumSamples == 0
  UnusedSlotNotZero,   // NumSamples == 1 but sample slot 1 is not zeroed (dk2.md §3)
  OutOfRange,          // a field outside what the hardware can produce
  UnsupportedVersion,  // lens distortion other than CatmullRom10 (dk2.md §2, 0x16)
  TimestampBackwards,  // sensor timestamp older than the previous report's
  Duplicate,           // same timestamp and sample count as the previous report
  kCount
};
constexpr size_t kRejectKinds = size_t(Reject::kCount);

const char* describe(Reject reason);

struct DecodeStats {
  uint64_t accepted = 0;
  std::array<uint64_t, kRejectKinds> rejected{};  // indexed by Reject
  uint64_t droppedSamples = 0;  // IMU samples missing between accepted reports (SampleCount)
  uint64_t resyncs = 0;         // timestamp gaps too long to bridge (SensorStream)

  void count(Reject r) { r == Reject::None ? ++accepted : ++rejected[size_t(r)]; }
  uint64_t rejectedTotal() const;
  uint64_t rejectedFor(Reject r) const { return rejected[size_t(r)]; }
  std::string summary() const;  // one line, for logs
};

// A decoded value, or the reason it was rejected.
template <class T>
struct Decoded {
  std::optional<T> value;
  Reject reason = Reject::None;
  explicit operator bool() const { return value.has_value(); }
  const T& operator*() const { return *value; }
  const T* operator->() const { return &*value; }
};

template <class T>
Decoded<T> rejected(Reject r, DecodeStats* stats) {
  if (stats) stats->count(r);
  return {std::nullopt, r};
}
template <class T>
Decoded<T> accepted(T value, DecodeStats* stats) {
  if (stats) stats->count(Reject::None);
  return {std::move(value), Reject::None};
}

}  // namespace photovr::hmd
