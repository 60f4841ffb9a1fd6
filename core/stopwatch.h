// Wall-clock stage timing, one definition for every module that reports stage times.
#pragma once

#include <chrono>
#include <ctime>

namespace photovr {

using Clock = std::chrono::steady_clock;

inline double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

inline double msSince(Clock::time_point t0) {
  return msBetween(t0, Clock::now());
}

// CPU time of the whole process, all threads (llvmpipe's included), in milliseconds: on a
// machine whose GL runs on the CPU, the work a pass costs whatever else shares the cores.
inline double processCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

}  // namespace photovr
