#include "harness/bench_limits.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <utility>

#include "core/stopwatch.h"
#include "gl/gbuffer_readback.h"
#include "hybrid/frame_pipeline.h"
#include "trace/pixel_estimate.h"
#include "hmd/headset_description.h"

namespace photovr::harness {
namespace {

template <typename F>
double bestMs(int repeats, F&& f) {
  double best = 1e30;
  for (int k = 0; k < repeats; ++k) {
    const auto t0 = Clock::now();
    f();
    best = std::min(best, msSince(t0));
  }
  return best;
}

// The hit count is returned so that the traversal cannot be optimised away.
uint64_t replayParallel(const EmbreeScene& embree, const std::vector<RecordedRay>& rays) {
  const ReplayCounts n = embree.replayParallel(rays);
  return n.hits + n.blocked;
}

// Times 'frame' (which returns its tracer milliseconds and rays) against the replay of the
// rays it cast, recorded on a first untimed call.
template <typename Frame>
void measure(TraceLimit& out, EmbreeScene& embree, Frame&& frame) {
  RayRecorder recorder;
  embree.setRecorder(&recorder);
  frame();
  embree.setRecorder(nullptr);
  const std::vector<RecordedRay> rays = recorder.take();
  double tracerMs = 1e30, rawMs = 1e30;
  for (int k = 0; k < 3; ++k) {
    const auto [ms, count] = frame();
    tracerMs = std::min(tracerMs, ms);
    out.rays = count;
    rawMs = std::min(rawMs, bestMs(1, [&] { replayParallel(embree, rays); }));
  }
  out.photovrMraysPerSecond = double(out.rays) / (tracerMs * 1e3);
  out.rawMraysPerSecond = double(rays.size()) / (rawMs * 1e3);
}

}  // namespace

std::array<TraceLimit, 2> measureTraceLimits(const BenchScene& s, int w, int h,
                                             gl::Context& context) {
  PipelineConfig config;
  config.layout = hmd::HeadsetDescription::dk2().layout(w, h);
  FramePipeline pipeline(*s.scene, config, &context);
  const auto cams = eyeCameras(s.view, w, h, 0, SamplerKind::Sobol);
  std::array<TraceLimit, 2> out{TraceLimit{s.scene->name, "hybrid"},
                                TraceLimit{s.scene->name, "pt"}};
  for (int m = 0; m < 2; ++m) {
    FrameRequest request{cams, 2, 0, {}};
    request.settings.mode = m == 0 ? FrameMode::Hybrid : FrameMode::PathTraced;
    // Warm-up: shader compilation, and the first touch of the storage each mode reuses.
    pipeline.recycle(pipeline.render(request));
    measure(out[m], pipeline.embree(), [&] {
      StereoFrame frame = pipeline.render(request);
      const auto result = std::pair{frame.times.cpuMs(), frame.times.rays};
      pipeline.recycle(std::move(frame));
      return result;
    });
  }
  return out;
}

GlLimit measureGlLimits(int w, int h) {
  const Scene empty;
  const gl::SceneGpu gpu(empty);
  gl::GBufferPass pass(w, h, gl::EyeRouting::Layered);
  const auto cams = eyeCameras(View{}, w, h, 0, SamplerKind::Sobol);
  std::array<glm::mat4, 2> vp;
  for (int e = 0; e < 2; ++e) vp[e] = cams[e].unjitteredProjection() * cams[e].view();
  GlLimit g{w, h};
  g.emptyFrameMs = bestMs(6, [&] {
    pass.render(gpu, cams, vp);
    pass.finish();
  });
  std::array<gl::GBufferImage, 2> images;  // reused, as the renderers do
  g.readbackMs = bestMs(6, [&] {
    for (int e = 0; e < 2; ++e) pass.read(e, images[e], gl::GBufferRead::Visibility);
  });
  gl::GBufferReadback pbo(pass, gl::GBufferRead::Visibility);
  g.pboReadbackMs = bestMs(6, [&] {
    pbo.start(2);
    pbo.finish(images);
  });
  return g;
}

}  // namespace photovr::harness
