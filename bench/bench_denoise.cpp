// The denoiser's cost and its worth at equal time (issue 5, "bench/").
//
// 1. Per-pass time of the denoiser (gl/denoiser.*) for both eyes at the DK2 eye resolution
//    (960x1080) and at half of it (480x540), modes 'temporal' and 'full', on a 1-spp hybrid
//    frame of the Cornell box. Each pass is bracketed by glFinish and timed on the CPU
//    clock (Denoiser::setTiming): under llvmpipe the "GPU" is the CPU, so that is the time
//    the pass costs. Steady state: 4 warm-up frames (shader JIT, and history long enough
//    for the temporal variance, SVGF §4.2), then the mean of --repeats frames.
// 2. Equal time, per scene, both eyes at --eq-width x --eq-height (default 240x270, where a
//    converged reference is affordable): the 1-spp denoised frame (without history, and
//    after 8 static frames of history) against an undenoised hybrid frame with as many
//    spp as fit in the 1-spp frame's tracing time plus the denoiser's time, i.e.
//    1 + floor(denoise / tracer CPU time of one spp). relMSE against the cached converged
//    reference of `photovr ab` (harness/reference_cache.*, --reference-spp, default 256).
// Writes bench_denoise_passes.csv and bench_denoise_equal_time.csv to --out (default
// out/bench).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "gl/render_context.h"
#include "core/options.h"
#include "harness/reference_cache.h"
#include "core/view.h"
#include "bench/bench_cli.h"
#include "core/builtin_scenes.h"
#include "core/gltf_loader.h"
#include "core/huge_pages.h"
#include "core/error.h"
#include "core/error_metrics.h"
#include "core/scene_transform.h"
#include "gl/denoiser.h"
#include "hybrid/denoise_input.h"
#include "hybrid/hybrid_renderer.h"

PHOTOVR_PREINIT(photovr::useHugePagesForMalloc);
namespace photovr {
namespace {

struct Args {
  std::string out = "out/bench";
  int repeats = 2;
  int eqWidth = 240, eqHeight = 270, referenceSpp = 256;
  std::vector<std::string> scenes = {"cornell", "spheres", "atrium"};
  bool skipPasses = false;
};

// The built-in scene seen from its first camera as `photovr ab` places it, so that the
// reference cache is shared with ab at the same size.
struct Setup {
  Scene scene;
  View view;
};
// A built-in scene by name, or a .gltf/.glb file (issue 22's glass scenes).
Scene sceneOf(const std::string& name) {
  const std::string ext = std::filesystem::path(name).extension().string();
  if (ext == ".gltf" || ext == ".glb") return loadGltf(name);
  return makeBuiltinScene(builtinSceneArgument(name));
}

Setup setupScene(const std::string& name) {
  Setup s{sceneOf(name), {}};
  s.view = resolveView(s.scene, Options({}, {}, {}));
  s.view.head = recenterOnView(s.scene, s.view.head);
  return s;
}

// Both eyes' denoiser inputs; 'images' must outlive them.
std::array<DenoiseInput, 2> inputsOf(const std::array<EyeImage, 2>& images) {
  return {makeDenoiseInput(images[0]), makeDenoiseInput(images[1])};
}

void denoise(gl::Denoiser& dn, const HybridRenderer& r, const std::array<DenoiseInput, 2>& in,
             gl::DenoiseMode mode, bool reset) {
  dn.run(r.gbuffer(), {in[0].eye, in[1].eye}, 2, mode, reset);
}

double totalMs(const std::vector<gl::PassTiming>& t) {
  double sum = 0.0;
  for (const gl::PassTiming& p : t) sum += p.ms;
  return sum;
}

// Mean per-pass times of 'repeats' steady-state frames; passes of the same name (the
// a-trous iterations) are listed separately in run order.
std::vector<gl::PassTiming> timePasses(gl::Denoiser& dn, const HybridRenderer& r,
                                       const std::array<DenoiseInput, 2>& in, gl::DenoiseMode mode,
                                       int repeats) {
  const int warmup = 4;
  std::vector<gl::PassTiming> mean;
  for (int k = 0; k < warmup + repeats; ++k) {
    denoise(dn, r, in, mode, k == 0);
    if (k < warmup) continue;
    if (mean.empty()) {
      mean = dn.timings();
      for (gl::PassTiming& p : mean) p.ms = 0.0;
    }
    for (size_t i = 0; i < mean.size(); ++i) mean[i].ms += dn.timings()[i].ms / repeats;
  }
  return mean;
}

void benchPasses(const Args& a, std::ofstream& csv) {
  std::printf(
      "\nPer-pass denoiser time, both eyes, 1-spp hybrid frame of cornell (ms, mean of %d"
      " steady-state frames, glFinish-bracketed):\n",
      a.repeats);
  csv << "eye_width,eye_height,mode,index,pass,ms\n";
  Setup s = setupScene("cornell");
  for (glm::ivec2 size : {glm::ivec2(960, 1080), glm::ivec2(480, 540)}) {
    HybridRenderer r(s.scene, size.x, size.y, TraceSettings{});
    const std::array<EyeImage, 2> images =
        r.render(eyeCameras(s.view, size.x, size.y, 0, SamplerKind::Sobol), 2, 0, nullptr);
    const std::array<DenoiseInput, 2> in = inputsOf(images);
    gl::Denoiser dn(size.x, size.y);
    dn.setTiming(true);
    for (gl::DenoiseMode mode : {gl::DenoiseMode::Temporal, gl::DenoiseMode::Full}) {
      const std::vector<gl::PassTiming> t = timePasses(dn, r, in, mode, a.repeats);
      std::printf("  %4dx%-4d x2 %-8s", size.x, size.y, gl::denoiseModeName(mode).c_str());
      for (size_t i = 0; i < t.size(); ++i) {
        std::printf(" %s %.1f", t[i].name.c_str(), t[i].ms);
        csv << size.x << ',' << size.y << ',' << gl::denoiseModeName(mode) << ',' << i << ','
            << t[i].name << ',' << t[i].ms << '\n';
      }
      std::printf(" | total %.1f\n", totalMs(t));
    }
  }
}

double relMseBothEyes(const std::array<EyeImage, 2>& img, const harness::Reference& ref) {
  return 0.5 * (relMse(img[0].color, ref.eyes[0]) + relMse(img[1].color, ref.eyes[1]));
}

double relMseBothEyes(const gl::Denoiser& dn, const harness::Reference& ref) {
  return 0.5 * (relMse(dn.readLinear(0), ref.eyes[0]) + relMse(dn.readLinear(1), ref.eyes[1]));
}

struct EqualTime {
  double traceMs = 1e30, tracerCpuMs = 1e30, denoiseMs = 1e30;  // best of the 8 frames
  double raw = 0.0, denoisedFirst = 0.0, denoised8 = 0.0;
  int spp = 0;
  double sppFrameMs = 0.0, sppRelMse = 0.0;
};

// 8 static frames of 1-spp hybrid + full denoising, then the N-spp undenoised frame.
EqualTime equalTime(const Setup& s, const harness::Reference& ref, const Args& a) {
  const int w = a.eqWidth, h = a.eqHeight;
  EqualTime e;
  HybridRenderer r(s.scene, w, h, TraceSettings{});
  gl::Denoiser dn(w, h);
  dn.setTiming(true);
  for (uint32_t f = 0; f < 8; ++f) {
    FrameTimes t;
    const std::array<EyeImage, 2> images =
        r.render(eyeCameras(s.view, w, h, f, SamplerKind::Sobol), 2, f, &t);
    const std::array<DenoiseInput, 2> in = inputsOf(images);
    denoise(dn, r, in, gl::DenoiseMode::Full, f == 0);
    // Frame 0 pays the shader JIT: not timed.
    if (f > 0) {
      e.traceMs = std::min(e.traceMs, t.totalMs());
      e.tracerCpuMs = std::min(e.tracerCpuMs, t.cpuMs());
      e.denoiseMs = std::min(e.denoiseMs, totalMs(dn.timings()));
    }
    if (f == 0) e.denoisedFirst = relMseBothEyes(dn, ref);
    if (f == 7) e.raw = relMseBothEyes(images, ref), e.denoised8 = relMseBothEyes(dn, ref);
  }
  // Each further sample costs about one 1-spp frame's tracer CPU time (the G-buffer and
  // its read-back are paid once).
  e.spp = 1 + int(e.denoiseMs / e.tracerCpuMs);
  TraceSettings many;
  many.samplesPerPixel = e.spp;
  HybridRenderer rm(s.scene, w, h, many);
  rm.render(eyeCameras(s.view, w, h, 0, SamplerKind::Sobol), 2, 0, nullptr);  // warm-up
  FrameTimes t;
  const std::array<EyeImage, 2> images =
      rm.render(eyeCameras(s.view, w, h, 8, SamplerKind::Sobol), 2, 8, &t);
  e.sppFrameMs = t.totalMs();
  e.sppRelMse = relMseBothEyes(images, ref);
  return e;
}

void benchEqualTime(const Args& a, std::ofstream& csv) {
  std::printf("\nEqual time, both eyes at %dx%d, relMSE against a %d-spp reference:\n", a.eqWidth,
              a.eqHeight, a.referenceSpp);
  std::printf("  %-8s %9s %9s | %9s %9s %9s | %4s %9s %9s | %s\n", "scene", "trace_ms", "denoise",
              "raw_1spp", "den_1st", "den_8th", "spp", "spp_ms", "spp_rel", "winner");
  csv << "scene,eye_width,eye_height,trace_1spp_ms,tracer_cpu_1spp_ms,denoise_ms,raw_relmse,"
         "denoised_no_history_relmse,denoised_8_frames_relmse,equal_time_spp,equal_time_frame_ms,"
         "equal_time_relmse,reference_spp\n";
  for (const std::string& name : a.scenes) {
    const Setup s = setupScene(name);
    const harness::Reference ref = harness::loadOrRenderReference(
        {&s.scene, s.view, a.eqWidth, a.eqHeight, 8}, a.referenceSpp);
    const EqualTime e = equalTime(s, ref, a);
    const char* winner = e.denoised8 < e.sppRelMse ? "denoised" : "more spp";
    std::printf("  %-8s %9.1f %9.1f | %9.4f %9.4f %9.4f | %4d %9.1f %9.4f | %s%s\n", name.c_str(),
                e.traceMs, e.denoiseMs, e.raw, e.denoisedFirst, e.denoised8, e.spp, e.sppFrameMs,
                e.sppRelMse, winner,
                e.denoisedFirst < e.sppRelMse ? " (even without history)" : "");
    csv << name << ',' << a.eqWidth << ',' << a.eqHeight << ',' << e.traceMs << ',' << e.tracerCpuMs
        << ',' << e.denoiseMs << ',' << e.raw << ',' << e.denoisedFirst << ',' << e.denoised8 << ','
        << e.spp << ',' << e.sppFrameMs << ',' << e.sppRelMse << ',' << ref.samplesPerPixel << '\n';
  }
}

const char* const kUsage =
    "usage: photovr_bench_denoise [--out DIR] [--repeats N] [--eq-width W] [--eq-height H]\n"
    "                             [--reference-spp N] [--scenes NAME|FILE] [--skip-passes]\n"
    "The denoiser's per-pass time for both eyes at 960x1080 and 480x540 (mean of --repeats\n"
    "steady-state frames, 2), and its worth at equal time against an undenoised frame with\n"
    "more spp at W x H (240x270) on every built-in scene or --scenes NAME|FILE, scored against a\n"
    "cached --reference-spp (256) reference. Writes bench_denoise_*.csv to --out (out/bench).\n";

Args parse(const Options& o) {
  Args a;
  a.out = o.text("--out", a.out);
  a.repeats = o.integer("--repeats", a.repeats, 1, 1000);
  a.eqWidth = o.integer("--eq-width", a.eqWidth, 8, 4096);
  a.eqHeight = o.integer("--eq-height", a.eqHeight, 8, 4096);
  a.referenceSpp = o.integer("--reference-spp", a.referenceSpp, 1, 1 << 20);
  if (o.has("--scenes")) a.scenes = {o.text("--scenes", "")};
  a.skipPasses = o.has("--skip-passes");
  return a;
}

int run(const Options& options) {
  const Args a = parse(options);
  const std::unique_ptr<gl::Context> ctx = gl::createRenderContext("");
  std::printf("bench_denoise: GL %s\n", ctx->renderer().c_str());
  std::filesystem::create_directories(a.out);
  if (!a.skipPasses) {
    std::ofstream passes(a.out + "/bench_denoise_passes.csv");
    benchPasses(a, passes);
  }
  std::ofstream eq(a.out + "/bench_denoise_equal_time.csv");
  benchEqualTime(a, eq);
  std::printf("wrote %s/bench_denoise_*.csv\n", a.out.c_str());
  return 0;
}

}  // namespace
}  // namespace photovr

int main(int argc, char** argv) {
  return photovr::benchMain(
      argc, argv, photovr::kUsage,
      {"--out", "--repeats", "--eq-width", "--eq-height", "--reference-spp", "--scenes"},
      {"--skip-passes"}, photovr::run);
}
