// Scratch storage a stage keeps from call to call (per thread, or per batcher).
#pragma once

#include <cstddef>
#include <vector>

namespace photovr {

// Grows 'v' to at least n elements and never shrinks it: a shrink and regrow constructs every
// element again. For the SIMD stages' groups (1-1.6 kB each) that is a copy of a zeroed
// temporary per group (12.6 % of prepareBrdfs' time on the reusing eye, `perf annotate`), and
// ~1000 default-constructed VertexShading per batch were a tenth of continuePaths' own time.
// Every element a call uses is written by that call before it is read.
template <typename T>
void growTo(std::vector<T>& v, size_t n) {
  if (v.size() < n) v.resize(n);
}

}  // namespace photovr
