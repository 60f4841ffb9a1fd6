// photovr view's renderer, running at its own rate beside the display loop: the G-buffer
// (GL, on the thread that owns the context) is drawn and read back when a frame starts, the
// Embree half (hybrid continuation or pure path tracing) runs on a worker thread while the
// main thread keeps compositing, and the finished frame is picked up by polling.
#pragma once

#include <array>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "core/camera.h"
#include "core/scene.h"
#include "gl/gbuffer.h"
#include "gl/scene_gpu.h"
#include "hybrid/hybrid_tracer.h"
#include "trace/embree_scene.h"
#include "trace/lights.h"
#include "trace/path_tracer.h"

namespace photovr::app {

struct FrameSettings {
  bool pathTraced = false;  // false: hybrid
  int spp = 1, bounces = 4;
  bool lensMatched = false;  // hybrid only: per-pixel spp from the lens (app/sample_maps.h)
};

struct FinishedFrame {
  uint32_t index = 0;
  std::array<EyeCamera, 2> eyes;
  std::array<EyeImage, 2> images;
  FrameSettings settings;
  double gbufferMs = 0.0, readbackMs = 0.0, traceMs = 0.0, totalMs = 0.0;
};

class ViewRenderer {
 public:
  // The GL context must be current on the calling thread; 'scene' must outlive this.
  ViewRenderer(const Scene& scene, const StereoLayout& eyes, bool hasLayerExtension);
  ~ViewRenderer();
  ViewRenderer(const ViewRenderer&) = delete;
  ViewRenderer& operator=(const ViewRenderer&) = delete;

  bool busy() const;
  // GL thread, when !busy(): draws and reads back the G-buffer, queues the tracing.
  void start(const std::array<EyeCamera, 2>& eyes, const FrameSettings& settings);
  // The finished frame, once; rethrows what the worker threw while tracing it.
  std::optional<FinishedFrame> take();
  // Hands a taken frame's images back when they are used up: the worker traces a later
  // frame into their storage instead of fresh memory (hybrid_tracer.h, HybridEyeBuffers).
  void recycle(std::array<EyeImage, 2>&& images);
  // The G-buffer of the last started frame (the denoiser's guides for that frame).
  const gl::GBufferPass& gbuffer() const { return pass_; }

 private:
  void workerLoop();
  FinishedFrame trace(FinishedFrame job, const std::array<gl::GBufferImage, 2>& g);

  const Scene& scene_;
  gl::SceneGpu gpu_;
  gl::GBufferPass pass_;
  EmbreeScene embree_;
  LightSet lights_;
  std::array<std::vector<uint16_t>, 2> lensMaps_;
  std::array<glm::mat4, 2> previousVp_{};
  uint32_t nextIndex_ = 0;

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<std::pair<FinishedFrame, std::array<gl::GBufferImage, 2>>> job_;
  std::optional<FinishedFrame> done_;
  // The traced job's G-buffer, handed back for the next read-back to reuse its storage
  // (gl::GBufferPass::read says why).
  std::array<gl::GBufferImage, 2> spare_;
  std::array<EyeImage, 2> spareImages_;         // from recycle(), for the worker
  std::array<HybridEyeBuffers, 2> eyeBuffers_;  // the worker's own
  std::exception_ptr failure_;
  bool working_ = false, quit_ = false;
  std::thread worker_;
};

}  // namespace photovr::app
