// Peak resident memory of the bench's process (each configuration runs in its own child
// process, app/bench_child.h, so this is the configuration's peak: scene, GL context,
// renderer, denoiser and frames together).
#pragma once

namespace photovr::app {

// VmHWM from /proc/self/status, else getrusage's ru_maxrss (the same figure on Linux).
double peakRssMiB();

}  // namespace photovr::app
