// Asynchronous read-back of a GBufferPass through pixel buffer objects: start() queues the
// copies of every target's layers into PBOs behind a fence and returns at once; finish()
// waits for the fence and maps. Two instances used alternately let the read-back of frame
// N overlap whatever the CPU does before finish() (e.g. tracing frame N - 1).
#pragma once

#include <array>
#include <vector>

#include "gl/gbuffer.h"

namespace photovr::gl {

class GBufferReadback {
 public:
  explicit GBufferReadback(const GBufferPass& pass, GBufferRead what = GBufferRead::All);
  ~GBufferReadback();
  GBufferReadback(const GBufferReadback&) = delete;
  GBufferReadback& operator=(const GBufferReadback&) = delete;

  void start(int eyeCount);  // after pass.render(); eyeCount 1 or 2 layers
  // Into 'out', reusing its storage (GBufferPass::read says why).
  void finish(std::array<GBufferImage, 2>& out);
  bool pending() const { return fence_ != nullptr; }

 private:
  struct Target {
    unsigned texture, format, type;
    size_t pixelBytes;
  };
  const GBufferPass& pass_;
  std::vector<Target> targets_;    // in GBufferTarget order, the depth last; or visibility alone
  std::vector<unsigned> buffers_;  // one PBO per target holding both layers
  void* fence_ = nullptr;
  int eyeCount_ = 0;
};

}  // namespace photovr::gl
