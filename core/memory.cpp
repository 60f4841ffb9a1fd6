#include "core/memory.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "core/error.h"

namespace photovr {

double peakRssMiB() {
  std::ifstream status("/proc/self/status");
  for (std::string key; status >> key;) {
    if (key == "VmHWM:") {
      double kib = 0.0;
      status >> kib;
      return kib / 1024.0;
    }
    status.ignore(1 << 20, '\n');
  }
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // Linux reports KiB
}

void checkFrameFitsInMemory(int width, int height, const char* options) {
  const double needed = kBytesPerEyePixel * double(width) * double(height);
  const double physical = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  if (physical <= 0.0 || needed <= physical) return;
  char message[256];
  std::snprintf(message, sizeof message,
                "%dx%d per eye needs about %.0f GB (%.0f bytes per eye pixel), more than this "
                "machine's %.0f GB",
                width, height, needed / 1e9, kBytesPerEyePixel, physical / 1e9);
  throw UsageError(std::string(options) + ": " + message);
}

}  // namespace photovr
