// GPU time of a stretch of GL commands, by a GL_TIME_ELAPSED query: what the device spent,
// without the driver's submission and the CPU's wait that a glFinish-bracketed clock adds
// (on a real GPU those are a large part of a sub-millisecond pass). Under llvmpipe the
// "device" is the CPU's rasterizer threads. Queries of one kind do not nest.
#pragma once

namespace photovr::gl {

class GpuTimer {
 public:
  GpuTimer();
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  void begin();
  void end();
  double ms() const;  // of the last begin/end; waits for the result

 private:
  unsigned query_ = 0;
};

}  // namespace photovr::gl
