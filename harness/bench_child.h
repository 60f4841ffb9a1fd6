// Runs one bench configuration in a child process, so that its peak resident memory is its
// own: memory a previous configuration freed but the allocator (or the GL driver) kept
// would otherwise count towards the next one's peak (measured: spheres at 120x135 showed
// 1082 MiB in-process after a DK2-size configuration, 202 MiB in a child of its own).
#pragma once

#include <functional>

#include "harness/bench_run.h"

namespace photovr::harness {

// Forks; the child runs 'work' and sends its frames, peak RSS and rejected-sample count
// back through a pipe. The calling process must not have started threads (TBB, GL):
// fork() copies only the calling thread. Throws std::runtime_error when the child fails
// (its error message is on stderr).
ConfigResult runInChild(const BenchConfig& config, const std::function<ConfigResult()>& work);

}  // namespace photovr::harness
