#include "core/progress.h"

#include <unistd.h>

#include <cstdio>

namespace photovr {

void reportProgress(double fraction, double raysPerSecond, double secondsLeft) {
  if (!isatty(STDERR_FILENO)) return;
  std::fprintf(stderr, "\r  %5.1f %%  %7.2f Mrays/s  %6.1f s left ", 100.0 * fraction,
               raysPerSecond * 1e-6, secondsLeft);
  if (fraction >= 1.0) std::fprintf(stderr, "\n");
}

}  // namespace photovr
