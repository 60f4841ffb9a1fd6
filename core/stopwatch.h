// Wall-clock stage timing, one definition for every module that reports stage times.
#pragma once

#include <chrono>

namespace photovr {

using Clock = std::chrono::steady_clock;

inline double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

inline double msSince(Clock::time_point t0) {
  return msBetween(t0, Clock::now());
}

}  // namespace photovr
