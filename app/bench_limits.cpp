#include "app/bench_limits.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <utility>

#include "core/stopwatch.h"
#include "gl/gbuffer_readback.h"
#include "hybrid/hybrid_renderer.h"
#include "trace/pixel_estimate.h"

namespace photovr::app {
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
  HybridRenderer renderer(
      *s.scene, w, h, context.hasExtension("GL_ARB_shader_viewport_layer_array"), TraceSettings{});
  const auto cams = eyeCameras(s.view, w, h, 0, SamplerKind::Sobol);
  std::array<TraceLimit, 2> out{TraceLimit{s.scene->name, "hybrid"},
                                TraceLimit{s.scene->name, "pt"}};
  // Warm-up: shader compilation, and the first touch of the storage both modes reuse.
  renderer.recycle(renderer.render(cams, 2, 0, nullptr));
  measure(out[0], renderer.embree(), [&] {
    HybridFrameTimes t;
    renderer.recycle(renderer.render(cams, 2, 0, &t));
    return std::pair{t.cpuMs(), t.rays};
  });
  std::array<EyeImage, 2> pt;
  for (int e = 0; e < 2; ++e) allocateEyeImage(pt[e], w, h);
  measure(out[1], renderer.embree(), [&] {
    const auto t0 = Clock::now();
    for (int e = 0; e < 2; ++e)
      pt[e] = renderPathTraced(renderer.traceContext(), cams[e], uint32_t(e), 0, std::move(pt[e]));
    return std::pair{msSince(t0), pt[0].rays + pt[1].rays};
  });
  return out;
}

GlLimit measureGlLimits(int w, int h, gl::Context& context) {
  const Scene empty;
  const gl::SceneGpu gpu(empty);
  gl::GBufferPass pass(w, h, context.hasExtension("GL_ARB_shader_viewport_layer_array"),
                       gl::EyeRouting::Layered);
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
    for (int e = 0; e < 2; ++e) pass.read(e, images[e]);
  });
  gl::GBufferReadback pbo(pass);
  g.pboReadbackMs = bestMs(6, [&] {
    pbo.start(2);
    pbo.finish(images);
  });
  return g;
}

}  // namespace photovr::app
