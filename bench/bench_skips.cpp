// What each skip of unneeded work saves (issue 7, item 3): for every built-in scene, the
// hybrid's frame time with all skips on, then with one skip turned off (trace/work_skips.h),
// plus the hidden-area mask (pixels the DK2 lens never shows) and converged accumulation
// (static view: stop when the estimated relMSE falls below a threshold). A skip that does
// not apply to a scene (it has that light class, say) is listed as such.
//
// Every skip acts on the tracer's side of the frame, so the time compared is that stage's
// (refit + hit rebuild + tracing, FrameTimes::cpuMs): the G-buffer pass on llvmpipe
// shares the cores and its time swings by +-10 % between identical runs, which hid the
// few-percent effects. Skip-on and skip-off runs alternate and each keeps its best of
// --repeats, so a busy spell hits both alike. The converged row is whole frames (process
// CPU time): there the skip drops whole frames.
// A light-class skip changes the noise too (a stand-in takes a share of light samples),
// so each row also has the estimated relMSE of its frames' mean and the time saved at equal
// error: time to a given error is proportional to time x relMSE (relMSE falls as 1/n).
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "hybrid/sample_maps.h"
#include "bench/bench_cli.h"
#include "core/builtin_scenes.h"
#include "core/huge_pages.h"
#include "gl/context.h"
#include "hybrid/hybrid_renderer.h"
#include "trace/convergence.h"

PHOTOVR_PREINIT(photovr::useHugePagesForMalloc);
namespace photovr {
namespace {

using SppMaps = StereoSampleMaps;

struct Config {
  std::string out = "out/bench";
  int width = 240, height = 270;  // a quarter of a DK2 eye per side, both eyes
  int frames = 6, repeats = 5;    // frames >= ConvergenceMonitor::kMinFrames (error estimate)
  // Converged accumulation: stop at this estimated relMSE. At 1 spp per frame the built-in
  // scenes reach 5e-2 in roughly 20 to 60 frames at this size.
  double converge = 5e-2;
  int convergeFrames = 64;
};

struct Timing {
  double msPerFrame = 1e30;
  uint64_t raysPerFrame = 0;
  double relMse = 0.0;  // estimated relMSE of the frames' mean (ConvergenceMonitor)
  double cost() const { return msPerFrame * relMse; }  // proportional to time at equal error
};

double cpuMs() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  const auto ms = [](const timeval& t) {
    return double(t.tv_sec) * 1e3 + double(t.tv_usec) * 1e-3;
  };
  return ms(u.ru_utime) + ms(u.ru_stime);
}

std::array<EyeCamera, 2> eyesOf(const Scene& scene, int w, int h, uint32_t frame) {
  StereoRig rig;
  rig.head = poseOf(scene.cameras.at(0));
  return {rig.eye(Eye::Left, w, h, samplePosition(SamplerKind::Sobol, frame)),
          rig.eye(Eye::Right, w, h, samplePosition(SamplerKind::Sobol, frame))};
}

// One run of o.frames stereo frames: lowers t to its CPU time per frame if it was faster.
void timeOnce(HybridRenderer& renderer, const Scene& scene, const Config& o, const SppMaps& maps,
              Timing& t) {
  uint64_t rays = 0;
  ConvergenceMonitor monitor;  // every repeat renders the same frames: one estimate suffices
  double ms = 0.0;
  for (int f = 0; f < o.frames; ++f) {
    FrameTimes times;
    const auto images = renderer.render(eyesOf(scene, o.width, o.height, uint32_t(f)), 2,
                                        uint32_t(f), &times, maps);
    ms += times.cpuMs();
    rays += images[0].rays + images[1].rays;
    for (int e = 0; e < 2; ++e) monitor.add(e, images[e].color, o.width);
  }
  t.msPerFrame = std::min(t.msPerFrame, ms / o.frames);
  t.raysPerFrame = rays / uint64_t(o.frames);
  t.relMse = monitor.estimatedRelMse();
}

// Two configurations alternately, best of o.repeats each.
std::pair<Timing, Timing> timePair(HybridRenderer& a, const SppMaps& mapsA, HybridRenderer& b,
                                   const SppMaps& mapsB, const Scene& scene, const Config& o) {
  Timing ta, tb;
  for (int r = 0; r < o.repeats; ++r) {
    timeOnce(a, scene, o, mapsA, ta);
    timeOnce(b, scene, o, mapsB, tb);
  }
  return {ta, tb};
}

// Whether turning 'skip' off changes any work for this scene.
bool applies(const Scene& scene, const std::string& skip) {
  WorkSkips off;
  off.disable(skip);
  if (skip == "punctual-lights" || skip == "area-lights" || skip == "environment")
    return LightSet(scene, off).standInCount() > 0;
  if (skip == "any-hit")
    return std::any_of(scene.meshes.begin(), scene.meshes.end(), [&](const Mesh& mesh) {
      const Material& m = scene.materials[mesh.material];
      return m.doubleSided && m.alphaMode != AlphaMode::Mask;
    });
  if (skip == "sky-pixels") return scene.environment.type != Environment::Type::None;
  if (skip == "dark-emitters")  // a textured emitter is instanced
    return std::any_of(scene.instances.begin(), scene.instances.end(), [&](const Instance& i) {
      const Material& m = scene.materials[scene.meshes[i.mesh].material];
      return m.isEmissive() && m.emissiveTexture.valid();
    });
  return true;  // refit: every built-in scene is static
}

struct Printer {
  std::ofstream csv;
  void row(const std::string& scene, const std::string& skip, const std::string& note,
           const Timing& on, const Timing& off) {
    const double saved = 1.0 - on.msPerFrame / off.msPerFrame;
    const double savedEqualError = off.cost() > 0.0 ? 1.0 - on.cost() / off.cost() : saved;
    std::printf("%-9s %-16s %8.1f %8.1f %7.1f%% %9.2e %9.2e %7.1f%% %10llu %10llu  %s\n",
                scene.c_str(), skip.c_str(), on.msPerFrame, off.msPerFrame, 100.0 * saved,
                on.relMse, off.relMse, 100.0 * savedEqualError, (unsigned long long)on.raysPerFrame,
                (unsigned long long)off.raysPerFrame, note.c_str());
    std::fflush(stdout);
    csv << scene << ',' << skip << ',' << on.msPerFrame << ',' << off.msPerFrame << ',' << saved
        << ',' << on.relMse << ',' << off.relMse << ',' << savedEqualError << ',' << on.raysPerFrame
        << ',' << off.raysPerFrame << ",\"" << note << "\"\n";
  }
};

// Converged accumulation: frames to reach the threshold vs rendering all of them.
void convergedRow(HybridRenderer& renderer, const Scene& scene, const std::string& name,
                  const Config& o, Printer& p) {
  ConvergenceMonitor monitor;
  int stoppedAt = o.convergeFrames;
  const double t0 = cpuMs();
  for (int f = 0; f < o.convergeFrames; ++f) {
    const auto images =
        renderer.render(eyesOf(scene, o.width, o.height, uint32_t(f)), 2, uint32_t(f), nullptr);
    for (int e = 0; e < 2; ++e) monitor.add(e, images[e].color, o.width);
    if (stoppedAt == o.convergeFrames && monitor.converged(o.converge)) stoppedAt = f + 1;
  }
  const double msPerFrame = (cpuMs() - t0) / o.convergeFrames;
  // Per presented frame over the run: tracing stops at 'stoppedAt', presenting goes on (no
  // error columns: the point is to stop once the error is low enough).
  const Timing off{msPerFrame, 0, 0.0}, on{msPerFrame * stoppedAt / o.convergeFrames, 0, 0.0};
  char note[128];
  std::snprintf(note, sizeof note, "stopped after %d of %d frames at estimated relMSE < %.0e",
                stoppedAt, o.convergeFrames, o.converge);
  p.row(name, "converged", note, on, off);
}

// The built-in scenes, cornell made double-sided everywhere: the only one whose meshes
// need no any-hit filter (every built-in has single-sided or MASK materials), and cornell
// lit by a textured panel (the only textured emitter).
std::vector<std::string> sceneNames() {
  std::vector<std::string> names = builtinSceneNames();
  names.push_back("cornell2s");
  names.push_back("cornell-textured-light");
  return names;
}

Scene sceneNamed(const std::string& name) {
  if (name == "cornell-textured-light") return makeCornellTexturedLight();
  if (name != "cornell2s") return makeBuiltinScene(name);
  Scene s = makeBuiltinScene("cornell");
  for (Material& m : s.materials) m.doubleSided = true;
  return s;
}

void benchScene(const std::string& name, const Config& o, Printer& p) {
  const Scene scene = sceneNamed(name);
  HybridRenderer base(scene, o.width, o.height, TraceSettings{});
  // The skip-on configuration is timed once per row: the spread of those identical timings
  // is the noise floor below which a row's saving means nothing.
  double lowest = 1e30, highest = 0.0;
  const auto noted = [&](const Timing& on) {
    lowest = std::min(lowest, on.msPerFrame), highest = std::max(highest, on.msPerFrame);
  };
  for (const std::string& skip : WorkSkips::names()) {
    if (!applies(scene, skip)) {
      std::printf("%-9s %-16s (does not apply: the scene needs this work)\n", name.c_str(),
                  skip.c_str());
      continue;
    }
    TraceSettings settings;
    settings.skips.disable(skip);
    HybridRenderer renderer(scene, o.width, o.height, settings);
    const auto [on, off] = timePair(base, {}, renderer, {}, scene, o);
    noted(on);
    p.row(name, skip, "", on, off);
  }
  const auto maps =
      lensSampleMaps(SampleMapKind::HiddenArea, StereoLayout::dk2(o.width, o.height), 1);
  const auto [hidden, uniform] = timePair(base, maps, base, {}, scene, o);
  noted(uniform);
  p.row(name, "hidden-area", describeSampleMaps(maps), hidden, uniform);
  convergedRow(base, scene, name, o, p);
  std::printf("%-9s noise: the identical all-skips-on timing ranged %.1f-%.1f ms (%.0f %%)\n",
              name.c_str(), lowest, highest, 100.0 * (highest / lowest - 1.0));
  p.csv << name << ",noise," << lowest << ',' << highest << ",,,,,,,\n";
}

const char* const kUsage =
    "usage: photovr_bench_skips [--out DIR] [--width W] [--height H] [--frames N] [--repeats N]\n"
    "                           [--scene NAME]\n"
    "Each skip of work a scene does not need, turned off one at a time: hybrid at W x H\n"
    "(240x270), 1 spp, N frames (6, at least 4), best of --repeats (5) alternating runs, and\n"
    "the converged-accumulation stop, on every bench scene (the built-ins, cornell2s,\n"
    "cornell-textured-light) or --scene NAME; writes bench_skips.csv to --out (out/bench).\n";

int run(const Options& options) {
  Config o;
  o.out = options.text("--out", o.out);
  o.width = options.integer("--width", o.width, 1, 4096);
  o.height = options.integer("--height", o.height, 1, 4096);
  o.frames = options.integer("--frames", o.frames, ConvergenceMonitor::kMinFrames, 100000);
  o.repeats = options.integer("--repeats", o.repeats, 1, 1000);
  const std::unique_ptr<gl::Context> ctx = gl::Context::createHeadless();
  std::printf(
      "bench_skips: hybrid, %dx%d x 2 eyes, 1 spp, %d frames, tracer-stage ms per frame "
      "(converged: whole-frame CPU ms), best of %d; GL: %s\n",
      o.width, o.height, o.frames, o.repeats, ctx->renderer().c_str());
  std::printf("%-9s %-16s %8s %8s %8s %9s %9s %8s %10s %10s\n", "scene", "skip", "on ms", "off ms",
              "saved", "relMSE on", "off", "eq.error", "rays on", "rays off");
  std::filesystem::create_directories(o.out);
  Printer p{std::ofstream(o.out + "/bench_skips.csv")};
  p.csv << "scene,skip,on_ms_per_frame,off_ms_per_frame,time_saved,on_relmse,off_relmse,"
           "time_saved_at_equal_error,on_rays_per_frame,off_rays_per_frame,note\n";
  const std::string only = options.text("--scene", "");
  const std::vector<std::string> names = sceneNames();
  if (!only.empty() && std::find(names.begin(), names.end(), only) == names.end())
    throw UsageError("--scene: '" + only + "' is none of the bench's scenes");
  for (const std::string& name : names)
    if (only.empty() || name == only) benchScene(name, o, p);
  std::printf("wrote %s/bench_skips.csv\n", o.out.c_str());
  return 0;
}

}  // namespace
}  // namespace photovr

int main(int argc, char** argv) {
  return photovr::benchMain(argc, argv, photovr::kUsage,
                            {"--out", "--width", "--height", "--frames", "--repeats", "--scene"},
                            {}, photovr::run);
}
