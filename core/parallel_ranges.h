// Whole-image passes (a value per pixel, each independent of the others) run over the
// cores in chunks, so that a pass the frame pays every time shrinks with the tracer as
// cores are added instead of staying a fixed serial cost (docs/MEASUREMENTS.md, "Serial
// passes left in the frame"). Each element is computed as a serial loop would, so the
// results are the same bits.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstddef>

namespace photovr {

// Elements per task: a few hundred KB of a pass's planes, many tasks per core at 960x1080.
constexpr size_t kRangeGrain = 4096;

// body(begin, end) over disjoint ranges covering [0, n).
template <typename Body>
void parallelRanges(size_t n, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kRangeGrain),
                    [&](const tbb::blocked_range<size_t>& r) { body(r.begin(), r.end()); });
}

}  // namespace photovr
