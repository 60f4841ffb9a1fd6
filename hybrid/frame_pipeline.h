// The stereo frame, from eye cameras to what the display shows: one object owns the scene's
// GPU data and G-buffer, the Embree scene and lights (hybrid_renderer.h), the reused eye
// buffers, the lens's sample maps, the optional denoiser and, for pt, the G-buffer that only
// guides it. Every command (render, render --hmd, view, ab, bench) renders through it.
//
// A frame has three stages, on two kinds of thread:
//   begin  (GL thread)   hybrid: draw the G-buffer and read it back; pt with the denoiser:
//                        draw it for the guides only;
//   trace  (any thread)  hybrid: rebuild each hit and continue its paths; pt: whole paths;
//   finish (GL thread)   the denoiser (demodulated lobes, guided by the frame's G-buffer),
//                        or, for a display, the noisy colour and depth uploaded as is.
// Scheduling: render() runs the three in a row (sequential); renderSequence() can instead
// queue frame N + 1's G-buffer before tracing N (pipelined: GL work overlaps tracing, no
// denoiser, whose guides would be N + 1's); start()/take() trace on a background worker
// while the GL thread keeps compositing (photovr view).
#pragma once

#include <array>
#include <condition_variable>
#include <exception>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "core/camera.h"
#include "core/scene.h"
#include "gl/context.h"
#include "gl/denoiser.h"
#include "gl/eye_arrays.h"
#include "hybrid/denoise_input.h"
#include "hybrid/frame_settings.h"
#include "hybrid/hybrid_renderer.h"
#include "hybrid/sample_maps.h"
#include "trace/caustics.h"
#include "trace/path_tracer.h"

namespace photovr {

// The tracer's share of a frame's settings (spp, bounces, seed, sampler) with the skips
// the scene was built for.
TraceSettings traceSettingsOf(const FrameSettings& settings, const WorkSkips& skips = {});

// What stays for the pipeline's life.
struct PipelineConfig {
  StereoLayout layout;  // eye-buffer size (width x height) and the FOVs the sample maps use
  hmd::LensModel lens;  // the headset's lens, for the sample maps
  WorkSkips skips;      // the Embree scene and lights are built for these
  gl::DenoiseParams denoiser;
  bool timeDenoiserPasses = false;  // glFinish around each pass (FrameTimes::denoisePassMs)
  bool forDisplay = false;  // undenoised frames are uploaded too: StereoFrame::display is set
};

struct FrameRequest {
  std::array<EyeCamera, 2> eyes;  // a mono view passes the same camera twice, eyeCount 1
  int eyeCount = 2;
  uint32_t index = 0;  // the frame number: jitter, random numbers, denoiser history
  FrameSettings settings;
  // The scene time the frame shows, in seconds, for a pipeline that animates its scene
  // (FramePipeline::animate); NaN: the scene as it stands.
  double sceneTime = std::numeric_limits<double>::quiet_NaN();
};

struct StereoFrame {
  FrameRequest request;
  std::array<EyeImage, 2> images;  // the traced (noisy) eyes
  FrameTimes times;
  bool denoised = false;    // the denoiser's output is this frame's
  gl::EyeTextures display;  // after finish(): the denoiser's, or the upload (forDisplay)
};

class FramePipeline {
 public:
  // 'context' must be current, or null for pt frames without the denoiser (no GL at all).
  // Keeps a reference to 'scene'.
  FramePipeline(const Scene& scene, const PipelineConfig& config, gl::Context* context);
  ~FramePipeline();
  FramePipeline(const FramePipeline&) = delete;
  FramePipeline& operator=(const FramePipeline&) = delete;

  // Makes up front what frames with these settings need (the denoiser: its textures and
  // programs; the sample maps), so that the first frame's times are the frame's alone.
  // Frames make it themselves otherwise.
  void prepare(const FrameSettings& settings);

  // Frames with a sceneTime pose 'scene' (the one this pipeline was built on; animated,
  // core/animation.h) at it before they are drawn or traced, with the last frame's pose as
  // the motion vectors' previous one (the first: kAnimationFrameSeconds before). Posing
  // happens on the GL thread while no frame is traced (begin()); pipelined scheduling, which
  // draws frame N + 1 while tracing N, refuses an animated scene (std::logic_error).
  void animate(Scene& scene);

  // Sequential: begin, trace and finish one frame.
  StereoFrame render(const FrameRequest& request);

  enum class Scheduling { Sequential, Pipelined };
  using RequestFn = std::function<FrameRequest(uint32_t frame)>;
  using FrameFn = std::function<void(StereoFrame& frame)>;
  // Frames [0, frames); each is handed to onFrame, then recycled. Pipelined refuses the
  // denoiser (std::logic_error). 'totals' sums the stage times (pipelined: gbufferMs is
  // only the CPU's wait for GL).
  void renderSequence(const RequestFn& requests, int frames, Scheduling scheduling,
                      const FrameFn& onFrame, FrameTimes* totals);

  // Background worker (GL thread calls all three): start() begins a frame and queues its
  // tracing when !busy(); take() returns it once traced, finished, or rethrows what the
  // worker threw.
  bool busy() const;
  void start(const FrameRequest& request);
  std::optional<StereoFrame> take();

  // Hands a frame back once its images are used up: a later frame is traced into their
  // storage instead of fresh memory (hybrid_tracer.h, HybridEyeBuffers).
  void recycle(StereoFrame&& frame);
  // The next denoised frame starts a new history (e.g. after untimed warm-up frames).
  void resetHistory() { historyValid_ = false; }

  const TraceContext& traceContext() const;  // the scene's tracer (ab times pt's rays on it)
  EmbreeScene& embree();  // e.g. to attach a RayRecorder (the bench's tracer limits)
  const gl::Denoiser* denoiser() const { return denoiser_.get(); }  // once a frame used it
  const StereoSampleMaps& sampleMaps(SampleMapKind kind, int spp);  // cached per (kind, spp)
  const PipelineConfig& config() const { return config_; }

 private:
  struct Job {
    StereoFrame frame;
    std::array<gl::GBufferImage, 2> gbuffers;
    const StereoSampleMaps* maps = nullptr;  // into maps_, chosen on the GL thread
  };
  void pose(StereoFrame& frame);
  void begin(Job& job);
  void trace(Job& job);
  void finish(StereoFrame& frame);
  void requireGl(const char* what) const;
  gl::Denoiser& denoiserForUse();
  void workerLoop();

  PipelineConfig config_;
  std::unique_ptr<HybridRenderer> hybrid_;  // with a GL context: G-buffer + continuation
  std::unique_ptr<EmbreeScene> embree_;     // without one: the tracer's scene alone
  std::unique_ptr<LightSet> lights_;
  std::unique_ptr<TraceContext> cpuContext_;
  std::unique_ptr<gl::Denoiser> denoiser_;     // made by the first denoised frame
  std::unique_ptr<gl::EyeArrays> upload_;      // forDisplay frames that skip the denoiser
  std::array<DenoiseInput, 2> denoiseInputs_;  // per eye, storage reused (denoise_input.h)
  std::vector<glm::vec4> uploadColor_;         // an eye's colour with alpha for upload_
  std::map<std::pair<SampleMapKind, int>, StereoSampleMaps> maps_;
  std::array<EyeImage, 2> ptBuffers_;         // pt frames are traced into these
  StereoPaths ptStereo_;                      // pt's left-eye paths for stereo reuse
  CausticPaths ptCaustics_;                   // pt's light paths, for both eyes of a frame
  std::array<gl::GBufferImage, 2> gbuffers_;  // sequential read-backs, storage reused
  bool historyValid_ = false;
  FrameMode historyMode_ = FrameMode::Hybrid;
  Scene* animated_ = nullptr;  // set by animate()
  double posedTime_ = std::numeric_limits<double>::quiet_NaN();

  // Background worker state, guarded by mutex_.
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<Job> job_;
  std::optional<StereoFrame> done_;
  std::array<gl::GBufferImage, 2> spareGBuffers_;
  std::array<EyeImage, 2> recycled_;  // from recycle(), taken by the next trace
  std::exception_ptr failure_;
  bool working_ = false, quit_ = false;
  std::thread worker_;  // started by the first start()
};

}  // namespace photovr
