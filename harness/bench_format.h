// Number formatting shared by the bench's writers: NaN (an unscored value) becomes 'none'.
#pragma once

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

namespace photovr::harness {

inline std::string formatNumber(double v, const char* format = "%.6g", const char* none = "") {
  if (!std::isfinite(v)) return none;
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

inline std::ofstream openBenchOutput(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  return out;
}

}  // namespace photovr::harness
