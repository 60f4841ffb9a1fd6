// Per-stage times of the hybrid frame against pure path tracing (issue 4, "bench/").
//
// For each built-in scene, both eyes at --width x --height, 1 spp, 8 bounces: hybrid stages
// (G-buffer, synchronous read-back, hit rebuild, trace) and the pipelined frame time (PBO
// read-back, G-buffer N+1 queued before tracing N), pt stages (primary hits, the rest),
// rays per second of each, and the ratio to raw Embree on the same rays (recorded on one
// untimed frame and replayed through rtcIntersect1 / rtcOccluded1). Best of --repeats.

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "bench/bench_cli.h"
#include "core/builtin_scenes.h"
#include "core/huge_pages.h"
#include "core/stopwatch.h"
#include "gl/context.h"
#include "hybrid/hybrid_renderer.h"
#include "trace/pixel_estimate.h"
#include "trace/primary_rays.h"

PHOTOVR_PREINIT(photovr::useHugePagesForMalloc);
namespace photovr {
namespace {

struct Row {
  std::string scene;
  FrameTimes hybrid;  // best frame
  double hybridFrameMs = 1e30, pipelinedFrameMs = 1e30;
  double ptFrameMs = 1e30, ptPrimaryMs = 1e30;
  uint64_t hybridRays = 0, ptRays = 0;
  double rawHybridMs = 1e30, rawPtMs = 1e30;
};

std::array<EyeCamera, 2> eyesOf(const Scene& s, int w, int h, uint32_t f) {
  StereoRig rig;
  rig.head = poseOf(s.cameras.at(0));
  return {rig.eye(Eye::Left, w, h, samplePosition(SamplerKind::Sobol, f)),
          rig.eye(Eye::Right, w, h, samplePosition(SamplerKind::Sobol, f))};
}

// Replays in parallel over chunks on all threads, as the tracer traced them.
double replayMs(const EmbreeScene& embree, const std::vector<RecordedRay>& rays) {
  const auto t0 = Clock::now();
  embree.replayParallel(rays);
  return msSince(t0);
}

void measureHybrid(HybridRenderer& r, const Scene& s, int w, int h, int repeats, Row& row) {
  RayRecorder recorder;
  r.embree().setRecorder(&recorder);
  // Warm-up (shader JIT, the first touch of the storage every frame reuses), ray recording.
  r.recycle(r.render(eyesOf(s, w, h, 0), 2, 0, nullptr));
  r.embree().setRecorder(nullptr);
  const std::vector<RecordedRay> rays = recorder.take();
  for (int k = 0; k < repeats; ++k) {
    FrameTimes t;
    r.recycle(r.render(eyesOf(s, w, h, uint32_t(k)), 2, uint32_t(k), &t));
    if (t.totalMs() < row.hybridFrameMs) row.hybridFrameMs = t.totalMs(), row.hybrid = t;
    row.hybridRays = t.rays;
    row.rawHybridMs =
        std::min(row.rawHybridMs, replayMs(r.embree(), rays) * double(t.rays) / rays.size());
    const auto t0 = Clock::now();
    r.renderSequence([&](uint32_t f) { return eyesOf(s, w, h, f); }, 3, 2, true,
                     [](uint32_t, std::array<EyeImage, 2>&) {}, nullptr);
    row.pipelinedFrameMs = std::min(row.pipelinedFrameMs, msSince(t0) / 3.0);
  }
}

void measurePt(const TraceContext& ctx, const Scene& s, int w, int h, int repeats, Row& row) {
  std::array<EyeImage, 2> last;  // traced into, touched once untimed as the hybrid's warm-up
  for (int e = 0; e < 2; ++e) allocateEyeImage(last[e], w, h);
  for (int k = 0; k < repeats; ++k) {
    const auto eyes = eyesOf(s, w, h, uint32_t(k));
    double primary = 0.0;
    for (int e = 0; e < 2; ++e) primary += timePrimaryRays(s, ctx.embree, eyes[e]).milliseconds;
    const auto t0 = Clock::now();
    uint64_t rays = 0;
    for (int e = 0; e < 2; ++e) {
      last[e] = renderPathTraced(ctx, eyes[e], uint32_t(e), uint32_t(k), std::move(last[e]));
      rays += last[e].rays;
    }
    const double ms = msSince(t0);
    row.ptFrameMs = std::min(row.ptFrameMs, ms);
    row.ptPrimaryMs = std::min(row.ptPrimaryMs, primary);
    row.ptRays = rays;
  }
}

void print(const Row& r, std::ofstream& csv) {
  const FrameTimes& h = r.hybrid;
  std::printf(
      "%-8s hybrid %7.1f ms (G-buffer %6.1f, read-back %5.1f, rebuild %5.1f, trace %7.1f)"
      " pipelined %7.1f ms | pt %7.1f ms (primary hits %5.1f)\n",
      r.scene.c_str(), r.hybridFrameMs, h.gbufferMs, h.readbackMs, h.rebuildMs, h.traceMs,
      r.pipelinedFrameMs, r.ptFrameMs, r.ptPrimaryMs);
  const double hyMrays = r.hybridRays / h.cpuMs() * 1e-3, ptMrays = r.ptRays / r.ptFrameMs * 1e-3;
  std::printf("         tracer Mrays/s: hybrid %.2f (raw Embree %.2f, ratio %.2f), pt %.2f\n",
              hyMrays, r.hybridRays / r.rawHybridMs * 1e-3, r.rawHybridMs / h.traceMs, ptMrays);
  csv << r.scene << ',' << r.hybridFrameMs << ',' << h.gbufferMs << ',' << h.readbackMs << ','
      << h.rebuildMs << ',' << h.traceMs << ',' << r.pipelinedFrameMs << ',' << r.ptFrameMs << ','
      << r.ptPrimaryMs << ',' << hyMrays << ',' << ptMrays << ',' << r.rawHybridMs / h.traceMs
      << '\n';
}

const char* const kUsage =
    "usage: photovr_bench_hybrid [--out DIR] [--width W] [--height H] [--repeats N]\n"
    "Stage times of the hybrid frame (G-buffer, read-back, hit rebuild, trace, pipelined)\n"
    "against pt on every built-in scene, both eyes at W x H (240x270), 1 spp, 8 bounces,\n"
    "best of N (3); writes bench_hybrid.csv to --out (out/bench).\n";

int run(const Options& o) {
  const std::string out = o.text("--out", "out/bench");
  const int w = o.integer("--width", 240, 1, 4096), h = o.integer("--height", 270, 1, 4096);
  const int repeats = o.integer("--repeats", 3, 1, 1000);
  const std::unique_ptr<gl::Context> ctx = gl::Context::createHeadless();
  std::printf("bench_hybrid: %dx%d x 2 eyes, 1 spp, 8 bounces, best of %d; GL: %s\n", w, h, repeats,
              ctx->renderer().c_str());
  std::filesystem::create_directories(out);
  std::ofstream csv(out + "/bench_hybrid.csv");
  csv << "scene,hybrid_ms,gbuffer_ms,readback_ms,rebuild_ms,trace_ms,pipelined_ms,pt_ms,"
         "pt_primary_ms,hybrid_tracer_mrays,pt_mrays,hybrid_raw_ratio\n";
  for (const std::string& name : builtinSceneNames()) {
    const Scene scene = makeBuiltinScene(name);
    HybridRenderer renderer(scene, w, h, TraceSettings{});
    Row row;
    row.scene = name;
    measureHybrid(renderer, scene, w, h, repeats, row);
    measurePt(renderer.traceContext(), scene, w, h, repeats, row);
    print(row, csv);
  }
  std::printf("wrote %s/bench_hybrid.csv\n", out.c_str());
  return 0;
}

}  // namespace
}  // namespace photovr

int main(int argc, char** argv) {
  return photovr::benchMain(argc, argv, photovr::kUsage,
                            {"--out", "--width", "--height", "--repeats"}, {}, photovr::run);
}
