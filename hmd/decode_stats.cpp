#include "hmd/decode_stats.h"

#include <numeric>

namespace photovr::hmd {

const char* describe(Reject reason) {
  switch (reason) {
    case Reject::None:
      return "accepted";
    case Reject::Empty:
      return "empty report";
    case Reject::WrongId:
      return "unexpected report ID";
    case Reject::Short:
      return "report shorter than its layout";
    case Reject::NoSamples:
      return "sensor report without samples";
    case Reject::UnusedSlotNotZero:
      return "unused sample slot not zeroed";
    case Reject::OutOfRange:
      return "field out of the hardware's range";
    case Reject::UnsupportedVersion:
      return "unsupported distortion version";
    case Reject::TimestampBackwards:
      return "timestamp went backwards";
    case Reject::Duplicate:
      return "duplicate report";
    case Reject::kCount:
      break;
  }
  return "unknown";
}

uint64_t DecodeStats::rejectedTotal() const {
  return std::accumulate(rejected.begin(), rejected.end(), uint64_t(0));
}

std::string DecodeStats::summary() const {
  std::string s =
      std::to_string(accepted) + " accepted, " + std::to_string(rejectedTotal()) + " rejected";
  for (size_t i = 1; i < kRejectKinds; ++i)
    if (rejected[i]) s += ", " + std::to_string(rejected[i]) + " " + describe(Reject(i));
  if (droppedSamples) s += ", " + std::to_string(droppedSamples) + " samples dropped";
  if (resyncs) s += ", " + std::to_string(resyncs) + " resyncs";
  return s;
}

}  // namespace photovr::hmd
