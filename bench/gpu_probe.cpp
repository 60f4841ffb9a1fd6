// The GL passes' cost on a real GPU (issue 6: compositor <= 1/4 of the G-buffer pass;
// issue 5: the denoiser's per-frame time), measured by GL_TIME_ELAPSED queries
// (gl/gpu_timer.h), for both eyes at the DK2's eye resolution on a 1920x1080 panel:
//   - the stereo-instanced G-buffer pass;
//   - the compositor (gl/timewarp.h) for a moved head (1.5 deg + 1 cm), a turned head,
//     and the frame as rendered (its floor);
//   - the SVGF denoiser's whole 'full' frame, and its passes (glFinish-bracketed).
// Built in the main tree like every bench, and on its own by bench/gpu_probe/CMakeLists.txt
// with EGL and glm alone, for a GPU machine that has none of photovr's other libraries
// (scripts/gpu_probe.sh). The denoiser's input is synthetic noise over the scene's
// G-buffer: its passes' cost does not depend on the values.
// Prints a table and writes gpu_probe.csv and gpu_probe_denoiser.csv to --out.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "bench/bench_cli.h"
#include "core/builtin_scenes.h"
#include "core/camera.h"
#include "core/stopwatch.h"
#include "gl/context.h"
#include "gl/denoiser.h"
#include "gl/gbuffer.h"
#include "gl/gpu_timer.h"
#include "gl/panel_output.h"
#include "gl/scene_gpu.h"
#include "gl/timewarp.h"
#include "hmd/lens.h"

namespace photovr {
namespace {

struct Config {
  std::string out = "out/bench";
  int eyeW = 960, eyeH = 1080, panelW = 1920, panelH = 1080;
  int repeats = 20;
  std::vector<std::string> scenes = builtinSceneNames();
};

std::array<EyeCamera, 2> eyesAt(const Pose& head, int w, int h) {
  StereoRig rig;
  rig.head = head;
  return {rig.eye(Eye::Left, w, h), rig.eye(Eye::Right, w, h)};
}

Pose turned(Pose p, float degrees, float metres) {
  p.orientation =
      glm::normalize(p.orientation * glm::angleAxis(glm::radians(degrees), glm::vec3(0, 1, 0)));
  p.position += p.orientation * glm::vec3(metres, 0.0f, 0.0f);
  return p;
}

// Median GPU time (timer query) and median glFinish-bracketed wall time of 'repeats' runs
// of each pass, the passes alternating, after one warm-up round (shader compilation on
// first use). On a GPU the query is the figure; llvmpipe's timer queries do not see its
// compute dispatches (measured: 0 ms), so there the wall time is.
struct GpuTime {
  double gpu = 0, wall = 0;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::vector<GpuTime> timePasses(int repeats, const std::vector<std::function<void()>>& passes) {
  gl::GpuTimer timer;
  std::vector<std::vector<double>> gpu(passes.size()), wall(passes.size());
  for (int round = 0; round <= repeats; ++round)
    for (size_t p = 0; p < passes.size(); ++p) {
      gl::waitForGpu();
      const auto t0 = Clock::now();
      timer.begin();
      passes[p]();
      timer.end();
      gl::waitForGpu();
      const double w = msSince(t0);
      if (round > 0) gpu[p].push_back(timer.ms()), wall[p].push_back(w);
    }
  std::vector<GpuTime> out;
  for (size_t p = 0; p < passes.size(); ++p) out.push_back({median(gpu[p]), median(wall[p])});
  return out;
}

// Deterministic noise in [0, 1) (a 32-bit integer hash, Wellons' lowbias32).
float noise(uint32_t x) {
  x ^= x >> 16, x *= 0x7feb352du, x ^= x >> 15, x *= 0x846ca68bu, x ^= x >> 16;
  return float(x >> 8) * (1.0f / 16777216.0f);
}

struct SyntheticEye {
  std::vector<glm::vec3> diffuse, specular, albedo, unfiltered;
  explicit SyntheticEye(size_t n, uint32_t seed)
      : diffuse(n), specular(n), albedo(n, glm::vec3(0.5f)), unfiltered(n, glm::vec3(0.0f)) {
    for (size_t i = 0; i < n; ++i) {
      const float a = noise(uint32_t(i) * 2u + seed), b = noise(uint32_t(i) * 2u + 1u + seed);
      diffuse[i] = glm::vec3(2.0f * a * a), specular[i] = glm::vec3(0.5f * b * b * b);
    }
  }
  gl::NoisyEye view(int w, int h) const {
    return {w, h, diffuse.data(), specular.data(), albedo.data(), albedo.data(), unfiltered.data()};
  }
};

struct SceneRow {
  std::string scene;
  GpuTime gbuffer, moved, turnedOnly, asRendered, denoiser;
  std::vector<gl::PassTiming> denoiserPasses;
};

SceneRow probeScene(const std::string& name, const Config& c) {
  const Scene scene = makeBuiltinScene(name);
  const gl::SceneGpu gpu(scene);
  gl::GBufferPass pass(c.eyeW, c.eyeH, gl::EyeRouting::Layered);
  hmd::LensModel lens;
  lens.panel.hResolution = c.panelW, lens.panel.vResolution = c.panelH;
  const std::array<FovTangents, 2> fov = {FovTangents::dk2LeftEye(),
                                          FovTangents::dk2LeftEye().mirrored()};
  gl::Timewarp timewarp(hmd::flattenLens(lens), c.eyeW, c.eyeH, fov);
  gl::PanelOutput panel(c.panelW, c.panelH, 90);
  const Pose head = poseOf(scene.cameras.at(0));
  const auto from = eyesAt(head, c.eyeW, c.eyeH);
  const auto moved = eyesAt(turned(head, 1.5f, 0.01f), c.eyeW, c.eyeH);
  const auto turn = eyesAt(turned(head, 1.5f, 0.0f), c.eyeW, c.eyeH);
  std::array<glm::mat4, 2> vp;
  for (int e = 0; e < 2; ++e) vp[e] = from[e].unjitteredProjection() * from[e].view();
  // As bench_compositor: the G-buffer's base colour and depth stand in for the frame.
  const unsigned color = pass.texture(gl::GBufferTarget::BaseColor), depth = pass.depthTexture();
  pass.render(gpu, from, vp);
  const size_t n = size_t(c.eyeW) * c.eyeH;
  const SyntheticEye left(n, 1u), right(n, 7u);
  const std::array<gl::NoisyEye, 2> noisy = {left.view(c.eyeW, c.eyeH), right.view(c.eyeW, c.eyeH)};
  gl::Denoiser denoiser(c.eyeW, c.eyeH);
  for (int f = 0; f < 4; ++f)  // history long enough for the temporal variance (SVGF §4.2)
    denoiser.run(pass, noisy, 2, gl::DenoiseMode::Full, false);
  const auto t =
      timePasses(c.repeats, {[&] { pass.render(gpu, from, vp); },
                             [&] { timewarp.runPanel(color, depth, from, moved, 1.0f, panel); },
                             [&] { timewarp.runPanel(color, depth, from, turn, 1.0f, panel); },
                             [&] { timewarp.runPanelAsRendered(color, from, 1.0f, panel); },
                             [&] { denoiser.run(pass, noisy, 2, gl::DenoiseMode::Full, false); }});
  SceneRow row{name, t[0], t[1], t[2], t[3], t[4], {}};
  denoiser.setTiming(true);
  denoiser.run(pass, noisy, 2, gl::DenoiseMode::Full, false);
  row.denoiserPasses = denoiser.timings();
  return row;
}

void report(const std::vector<SceneRow>& rows, const Config& c) {
  std::printf("%-8s | %-17s | %-17s %-17s %-17s | %-13s | %-17s\n", "", "gbuffer",
              "compositor moved", "turned", "as rendered", "moved/gbuffer", "denoiser (full)");
  std::printf("%-8s | %8s %8s | %8s %8s %8s %8s %8s %8s | %6s %6s | %8s %8s\n", "scene", "gpu",
              "wall", "gpu", "wall", "gpu", "wall", "gpu", "wall", "gpu", "wall", "gpu", "wall");
  std::ofstream csv(c.out + "/gpu_probe.csv");
  csv << "scene,eye_width,eye_height,panel_width,panel_height,gbuffer_gpu_ms,timewarp_moved_gpu_ms,"
         "timewarp_turned_gpu_ms,as_rendered_gpu_ms,denoiser_full_gpu_ms,gbuffer_wall_ms,"
         "timewarp_moved_wall_ms,timewarp_turned_wall_ms,as_rendered_wall_ms,denoiser_full_wall_"
         "ms\n";
  for (const SceneRow& r : rows) {
    std::printf(
        "%-8s | %8.3f %8.3f | %8.3f %8.3f %8.3f %8.3f %8.3f %8.3f | %6.3f %6.3f | %8.3f %8.3f\n",
        r.scene.c_str(), r.gbuffer.gpu, r.gbuffer.wall, r.moved.gpu, r.moved.wall, r.turnedOnly.gpu,
        r.turnedOnly.wall, r.asRendered.gpu, r.asRendered.wall, r.moved.gpu / r.gbuffer.gpu,
        r.moved.wall / r.gbuffer.wall, r.denoiser.gpu, r.denoiser.wall);
    csv << r.scene << ',' << c.eyeW << ',' << c.eyeH << ',' << c.panelW << ',' << c.panelH;
    for (const GpuTime* t : {&r.gbuffer, &r.moved, &r.turnedOnly, &r.asRendered, &r.denoiser})
      csv << ',' << t->gpu;
    for (const GpuTime* t : {&r.gbuffer, &r.moved, &r.turnedOnly, &r.asRendered, &r.denoiser})
      csv << ',' << t->wall;
    csv << '\n';
  }
  std::printf(
      "(ms, median of %d alternating runs: gpu = GL_TIME_ELAPSED query, wall = glFinish to "
      "glFinish; target: compositor moved <= 0.25 x gbuffer)\n",
      c.repeats);
  std::ofstream passes(c.out + "/gpu_probe_denoiser.csv");
  passes << "scene,pass,ms\n";
  for (const SceneRow& r : rows) {
    std::printf("denoiser passes, %s (glFinish-bracketed ms):", r.scene.c_str());
    for (const gl::PassTiming& p : r.denoiserPasses) {
      std::printf(" %s %.3f", p.name.c_str(), p.ms);
      passes << r.scene << ',' << p.name << ',' << p.ms << '\n';
    }
    std::printf("\n");
  }
}

const char* const kUsage =
    "usage: photovr_gpu_probe [--out DIR] [--repeats N] [--scene NAME] [--width W] [--height H]\n"
    "The G-buffer pass, the headset compositor and the denoiser timed by GL timer queries\n"
    "(median of --repeats, 20), both eyes at W x H (960x1080) on a 1920x1080 panel, on EGL;\n"
    "writes gpu_probe.csv and gpu_probe_denoiser.csv to --out (out/bench).\n";

Config parse(const Options& o) {
  Config c;
  c.out = o.text("--out", c.out);
  c.repeats = o.integer("--repeats", c.repeats, 1, 1000);
  c.eyeW = o.integer("--width", c.eyeW, 8, 4096);
  c.eyeH = o.integer("--height", c.eyeH, 8, 4096);
  if (o.has("--scene")) c.scenes = {builtinSceneArgument(o.text("--scene", ""))};
  return c;
}

int run(const Options& options) {
  const Config c = parse(options);
  const auto ctx = gl::Context::create({gl::Backend::EGL});
  std::printf("gpu_probe: %s; eyes %dx%d x 2, panel %dx%d\n", ctx->renderer().c_str(), c.eyeW,
              c.eyeH, c.panelW, c.panelH);
  std::filesystem::create_directories(c.out);
  std::vector<SceneRow> rows;
  for (const std::string& name : c.scenes) rows.push_back(probeScene(name, c));
  report(rows, c);
  return 0;
}

}  // namespace
}  // namespace photovr

int main(int argc, char** argv) {
  return photovr::benchMain(argc, argv, photovr::kUsage,
                            {"--out", "--repeats", "--scene", "--width", "--height"}, {},
                            photovr::run);
}
