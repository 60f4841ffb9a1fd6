// The hybrid's two halves: the stereo G-buffer in GL (one instanced draw per mesh for both
// eyes), read back, and each visible hit rebuilt from its visibility record and continued
// by Embree. hybrid/frame_pipeline.h builds the whole frame on it (pt, denoiser, display);
// tests of the hybrid itself use it directly.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <utility>

#include "core/camera.h"
#include "core/scene.h"
#include "gl/gbuffer.h"
#include "gl/scene_gpu.h"
#include "hybrid/hybrid_tracer.h"
#include "trace/caustics.h"
#include "trace/embree_scene.h"
#include "trace/lights.h"
#include "trace/sample_map.h"

namespace photovr {

// Stage times of a frame (FramePipeline fills the pt and finish() ones too).
struct FrameTimes {
  double gbufferMs = 0.0;   // GL: draw both eyes and wait for them (pt: the guides' draw)
  double readbackMs = 0.0;  // GL -> CPU copy of the G-buffer layers
  double rebuildMs = 0.0;   // visibility records -> exact hits
  double traceMs = 0.0;     // path continuation (pt: whole paths), both eyes
  // Per turn: [0] the eye traced first, [1] the second, which reuses the first's paths with
  // stereo reuse on (the eyes take turns, stereoTurnsOf; off: the left eye, then the right).
  std::array<double, 2> turnTraceMs{};        // its rebuild and trace
  std::array<uint64_t, 2> turnPaths{};        // paths from primary hits ...
  std::array<uint64_t, 2> turnReusedPaths{};  // ... of which reused the first eye's ...
  std::array<uint64_t, 2> turnOwnBounces{};   // ... of which traced an own bounce too
  std::array<double, 2> turnCausticMs{};      // of turnTraceMs: light-traced caustics
  uint64_t causticSplats = 0;                 // light paths that reached a pixel, both eyes
  double refitMs = 0.0;                       // BVH top-level re-commit (only with 'refit' off)
  double animateMs = 0.0;      // posing an animated scene and updating GL, Embree and lights to it
  double denoiseMs = 0.0;      // FramePipeline's finish: denoiser or upload, wall
  double denoisePassMs = 0.0;  // the denoiser's passes, glFinish-bracketed (timed)
  uint64_t rays = 0, outsideHits = 0, rejectedSamples = 0;
  double cpuMs() const { return refitMs + rebuildMs + traceMs; }  // the tracer's share
  double totalMs() const { return animateMs + gbufferMs + readbackMs + cpuMs(); }
  void add(const FrameTimes& t);                  // sums every field
  void addTurn(int turn, const EyeImage& image);  // its rays, rejected samples and path counts
};

// The tracer's side of a posed scene: skinned meshes' BVHs refit, the top level re-committed,
// and the light set rebuilt where lights or emitters moved.
void moveTracerScene(EmbreeScene& embree, LightSet& lights, const SceneMotion& motion);

class HybridRenderer {
 public:
  // The GL context must be current. Keeps a reference to 'scene'.
  HybridRenderer(const Scene& scene, int eyeWidth, int eyeHeight, const TraceSettings& settings);

  // Renders 'eyeCount' (1 or 2) eyes of frame 'frame'; a mono view passes the same camera
  // twice and eyeCount 1.
  std::array<EyeImage, 2> render(const std::array<EyeCamera, 2>& eyes, int eyeCount, uint32_t frame,
                                 FrameTimes* times, const StereoSampleMaps& samples = {});

  // The same in stages, for a caller that traces on another thread (FramePipeline's
  // background worker): GL thread: drawGBuffer, then readGBuffer into 'into' (the
  // visibility records alone, all the tracer reads: gl::GBufferRead; storage reused); any
  // thread: trace, with the given settings (spp, bounces, seed, sampler; the
  // skips stay the constructor's).
  void drawGBuffer(const std::array<EyeCamera, 2>& eyes);
  void readGBuffer(int eyeCount, std::array<gl::GBufferImage, 2>& into, FrameTimes& t);
  std::array<EyeImage, 2> trace(const std::array<gl::GBufferImage, 2>& g,
                                const std::array<EyeCamera, 2>& eyes, int eyeCount, uint32_t frame,
                                const TraceSettings& settings, FrameTimes& t,
                                const StereoSampleMaps& samples);

  // A sequence of frames. Pipelined: the G-buffer of frame N + 1 is drawn and its read-back
  // (pixel buffer objects) queued before frame N is traced, so GL work overlaps tracing;
  // sequential: each frame's G-buffer is drawn and read back synchronously, then traced.
  using CameraFn = std::function<std::array<EyeCamera, 2>(uint32_t frame)>;
  using FrameFn = std::function<void(uint32_t frame, std::array<EyeImage, 2>& images)>;
  void renderSequence(const CameraFn& cameras, int frames, int eyeCount, bool pipelined,
                      const FrameFn& onFrame, FrameTimes* totals);

  // Hands a frame's images back when the caller is done with them: the next frame is traced
  // into their storage instead of fresh memory (hybrid_tracer.h, HybridEyeBuffers).
  // renderSequence does it after each onFrame.
  void recycle(std::array<EyeImage, 2>&& images);

  // The scene was posed (core/animation.h poseScene returned 'motion'): the G-buffer's
  // instance data and skinned vertices, and the tracer's scene (moveTracerScene), follow it.
  // Not while a frame is being traced.
  void sceneMoved(const SceneMotion& motion);

  const gl::GBufferPass& gbuffer() const { return pass_; }
  const EmbreeScene& embree() const { return embree_; }
  EmbreeScene& embree() { return embree_; }  // e.g. to attach a RayRecorder (bench/)
  const TraceContext& traceContext() const { return ctx_; }
  void setSeed(uint32_t seed) { ctx_.settings.seed = seed; }
  // What render() and renderSequence() trace with from now on (the skips stay). A frame
  // traced after it traces its light-traced caustics anew, even if an earlier frame had its
  // index (so that each setting of an A/B pays for its own).
  void setSettings(const TraceSettings& s) {
    const WorkSkips skips = ctx_.settings.skips;
    ctx_.settings = s;
    ctx_.settings.skips = skips;
    caustics_.key = {};
  }

 private:
  const Scene& scene_;
  gl::SceneGpu gpu_;
  gl::GBufferPass pass_;
  std::array<gl::GBufferImage, 2> gbuffers_;    // the last read-back, its storage reused
  std::array<HybridEyeBuffers, 2> eyeBuffers_;  // the tracer's, likewise (see recycle())
  StereoPaths stereo_;                          // the left eye's paths for stereo reuse
  CausticPaths caustics_;                       // the light paths, for both eyes of a frame
  EmbreeScene embree_;
  LightSet lights_;
  TraceContext ctx_;

  std::array<glm::mat4, 2> previousViewProjection_{};
  bool hasPrevious_ = false;
};

}  // namespace photovr
