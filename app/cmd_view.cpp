// photovr view: the interactive app. A window shows the headset's panel image; the renderer
// (hybrid/frame_pipeline.h, its background worker) makes frames at its own rate while every display
// refresh re-projects the newest finished frame to the newest head pose, distorts it for the DK2's
// lenses and draws the Dear ImGui overlay on top.
//
// Clocks: the DK2 and a live replay report poses on the host clock (hmd::hostSeconds);
// a pose script runs from the moment the window opens. Frames start at the pose of "now";
// each refresh is shown at the pose predicted the headset's display latency ahead
// (hmd/headset_description.h; DK2: LibOVR's mid-scan-out target, 20.9 ms after present).
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>

#include <imgui.h>

#include "app/commands.h"
#include "app/headset.h"
#include "app/render_request.h"
#include "display/compositor.h"
#include "display/output.h"
#include "hmd/headset_description.h"
#include "core/memory.h"
#include "core/files.h"
#include "core/options.h"
#include "core/view.h"
#include "app/view_overlay.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/scene_transform.h"
#include "core/stopwatch.h"
#include "gl/headset_monitor.h"
#include "gl/window_input.h"
#include "hmd/dk2_driver.h"
#include "hybrid/frame_pipeline.h"

namespace photovr::app {
namespace {

const char* const kViewCommandHelp =
    "usage: photovr view [options]\n"
    "Opens a window showing the DK2 panel image: the renderer makes frames at its own rate,\n"
    "the compositor re-projects the newest one to the newest head pose at every refresh.\n"
    "  --scene NAME|FILE      atrium (default), cornell, spheres, or a .gltf/.glb file\n"
    "  --env FILE             equirectangular .hdr/.exr environment\n"
    "  --hmd dk2|replay FILE|sim FILE|none  head tracking (default none: the desktop\n"
    "                         camera, right-drag to look, WASD/E/Q to move, Shift faster);\n"
    "                         without a DK2, dk2 falls back to the desktop camera\n"
    "  --width W --height H   per-eye render size over the lens's field (default 320x360)\n"
    "  --overscan DEG         render DEG beyond the lens's field on every side (0..10, default\n"
    "                         0): head turns of up to DEG between frames show no black edge\n"
    "  --window WxH           window size (default 960x540)\n"
    "  --panel WxH            panel pixels (default: the window's; 1920x1080 with a DK2)\n"
    "  --rotate 0|90|180|270  panel output rotation (default 0; the DK2 scans at 90)\n"
    "  --mode hybrid|pt       renderer (default hybrid); --spp N (default 1), --bounces N\n"
    "                         (default 4), --denoise off|temporal|full (default full),\n"
    "                         --sampling uniform|lens-matched (default uniform),\n"
    "                         --stereo-reuse on|off (default on),\n"
    "                         --caustics on|off (default on),\n"
    "                         --exposure E (default 1); all of these change in the overlay\n"
    "  --no-reproject         show frames at the pose they were rendered at\n"
    "  --no-overlay           no Dear ImGui overlay\n"
    "  --out DIR              where F12 saves the panel image (default .)\n"
    "  --frames N             exit after N refreshes that showed a rendered frame\n"
    "  --screenshot FILE      with --frames: save the last refresh, overlay included (PNG)\n";

glm::ivec2 parseSize(const Options& o, const std::string& name, glm::ivec2 fallback) {
  if (!o.has(name)) return fallback;
  const std::string t = o.text(name, "");
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(t.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 2 || h < 1 ||
      w > 8192 || h > 8192)
    throw UsageError(name + ": '" + t + "' is not WIDTHxHEIGHT within 2..8192");
  return {w, h};
}

struct ViewConfig {
  hmd::HeadsetDescription headset = hmd::HeadsetDescription::dk2();
  Scene scene;
  View view;
  HmdSpec hmd;
  int width = 320, height = 360, rotation = 0, frames = 0;
  StereoLayout eyes;  // width x height over the lens's field, plus the overscan
  glm::ivec2 window{960, 540}, panel{0, 0};
  FrameSettings settings;  // mode, spp, bounces, sample map, denoiser; seed 0, Sobol
  bool reproject = true, overlay = true, rotationGiven = false;
  float exposure = 1.0f;
  double sceneTime = 0.0;  // an animated scene's clock: --time, then real time while playing
  bool animated = false, playing = true;
  std::string outDir = ".", screenshot;
};

const char* const kDenoiseModes[] = {"off", "temporal", "full"};
const char* const kModes[] = {"hybrid", "pt"};

ViewConfig parseViewConfig(Args args) {
  ViewConfig c;
  c.hmd = extractHmdOption(args);
  std::set<std::string> valued = {"--scene",    "--env",          "--width",   "--height",
                                  "--window",   "--panel",        "--rotate",  "--mode",
                                  "--spp",      "--bounces",      "--denoise", "--sampling",
                                  "--exposure", "--out",          "--frames",  "--screenshot",
                                  "--overscan", "--stereo-reuse", "--caustics"};
  valued.insert(kViewOptions.begin(), kViewOptions.end());
  const Options o(args, valued, {"--no-reproject", "--no-overlay"});
  if (!o.positional().empty())
    throw UsageError("view: unexpected argument '" + o.positional()[0] + "'");
  c.width = o.integer("--width", 320, 8, 4096);
  c.height = o.integer("--height", 360, 8, 4096);
  c.eyes =
      c.headset.layout(c.width, c.height, glm::radians(o.number("--overscan", 0.0f, 0.0f, 10.0f)));
  checkFrameFitsInMemory(c.eyes.width, c.eyes.height, "--width/--height");
  c.window = parseSize(o, "--window", c.window);
  c.panel = parseSize(o, "--panel", {0, 0});
  if (c.panel.x % 2) throw UsageError("--panel: the width must be even (two eyes)");
  c.rotation = std::stoi(o.choice("--rotate", "0", {"0", "90", "180", "270"}));
  c.rotationGiven = o.has("--rotate");
  c.settings.mode = o.choice("--mode", "hybrid", {"hybrid", "pt"}) == "pt" ? FrameMode::PathTraced
                                                                           : FrameMode::Hybrid;
  c.settings.spp = o.integer("--spp", 1, 1, 64);
  c.settings.bounces = o.integer("--bounces", 4, 0, 16);
  c.settings.sampleMap =
      parseSampleMapKind(o.choice("--sampling", "uniform", {"uniform", "lens-matched"}));
  c.settings.denoise = gl::parseDenoiseMode(o.text("--denoise", "full"));
  c.settings.stereoReuse = parseStereoReuse(o);
  c.settings.caustics = parseCaustics(o);
  c.exposure = o.number("--exposure", 1.0f, 1e-6f, 1e6f);
  c.reproject = !o.has("--no-reproject");
  c.overlay = !o.has("--no-overlay");
  c.outDir = o.text("--out", ".");
  createOutputFolder(c.outDir);
  c.frames = o.integer("--frames", 0, 1, 1000000);
  c.screenshot = o.text("--screenshot", "");
  if (!c.screenshot.empty() && !c.frames)
    throw UsageError("--screenshot: needs --frames N (it saves the last refresh)");
  c.scene = loadSceneSpec(o.text("--scene", "atrium"));
  applyEnvironmentOption(c.scene, o.text("--env", ""));
  c.sceneTime = applyTimeOption(c.scene, o);
  c.animated = isAnimated(c.scene);
  warnAboutScene(c.scene);
  c.view = resolveView(c.scene, o);
  if (!c.view.stereo || o.has("--fovy"))
    throw UsageError("view: --eyes and --fovy are not headset options (the eyes are the DK2's)");
  c.view.head = recenterOnView(c.scene, c.view.head);
  return c;
}

// The head pose source and its clock: seconds on the clock its poses are asked in.
struct Head {
  std::unique_ptr<hmd::HeadPoseSource> source;
  hmd::DesktopHeadset* desktop = nullptr;  // set when the desktop camera is used
  bool hostClock = false;
  double start = hmd::hostSeconds();
  double now() const { return hostClock ? hmd::hostSeconds() : hmd::hostSeconds() - start; }
};

Head openHead(const HmdSpec& spec) {
  Head h;
  std::string why;
  h.source = openHeadPoseSource(spec, true, &why);
  h.hostClock = spec.kind == "dk2" || spec.kind == "replay";
  if (!h.source) {
    if (spec.kind == "dk2") std::cerr << "photovr view: " << why << "; using the desktop camera\n";
    auto desktop = std::make_unique<hmd::DesktopHeadset>();
    h.desktop = desktop.get();
    h.source = std::move(desktop);
    h.hostClock = false;
  }
  return h;
}

hmd::DesktopInput desktopInput(const gl::WindowInput& in, float dt) {
  hmd::DesktopInput d;
  d.mouseDelta = in.mouseDelta;
  d.forward = in.forward, d.back = in.back, d.left = in.left, d.right = in.right;
  d.up = in.up, d.down = in.down, d.fast = in.fast;
  d.dt = dt;
  return d;
}

// What the overlay shows, smoothed where it jitters.
struct Stats {
  double displayMs = 0.0, compositorMs = 0.0, denoiseMs = 0.0;
  FrameRequest last;  // of the last frame shown, and its stage times
  FrameTimes lastTimes;
  double meanSpp = 0.0;
  int rendered = 0;
};

double meanSamples(const EyeImage& e) {
  double s = 0.0;
  for (uint32_t n : e.samples) s += n;
  return e.samples.empty() ? 0.0 : s / double(e.samples.size());
}

void drawOverlay(ViewConfig& c, const Stats& s, const Head& head) {
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("photovr", nullptr,
               ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoSavedSettings);
  ImGui::Text("display %.1f ms (%.0f Hz), compositor %.1f ms", s.displayMs,
              s.displayMs > 0 ? 1e3 / s.displayMs : 0.0, s.compositorMs);
  const FrameTimes& t = s.lastTimes;
  ImGui::Text("frame %u (%d done): %.0f ms", s.last.index, s.rendered, t.totalMs() + s.denoiseMs);
  ImGui::Text("  G-buffer %.1f, read-back %.1f, trace %.1f, denoise %.1f ms", t.gbufferMs,
              t.readbackMs, t.rebuildMs + t.traceMs, s.denoiseMs);
  if (s.last.settings.stereoReuse)  // the eyes take turns: by turn
    ImGui::Text(
        "  tracer first eye %.1f, second %.1f ms (%.0f %% of its paths reused)", t.turnTraceMs[0],
        t.turnTraceMs[1],
        t.turnPaths[1] ? 100.0 * double(t.turnReusedPaths[1]) / double(t.turnPaths[1]) : 0.0);
  else
    ImGui::Text("  tracer left eye %.1f, right %.1f ms", t.turnTraceMs[0], t.turnTraceMs[1]);
  ImGui::Text("  %s, %.2f spp mean, %d bounces", frameModeName(s.last.settings.mode), s.meanSpp,
              s.last.settings.bounces);
  if (c.animated) {
    ImGui::Text("  scene at %.2f s, posed in %.2f ms", s.last.sceneTime, t.animateMs);
    ImGui::Checkbox("play animation", &c.playing);
  }
  int mode = int(c.settings.mode);
  if (ImGui::Combo("mode", &mode, kModes, 2)) c.settings.mode = FrameMode(mode);
  ImGui::SliderInt("spp", &c.settings.spp, 1, 64);
  ImGui::SliderInt("bounces", &c.settings.bounces, 0, 16);
  int denoise = int(c.settings.denoise);
  if (ImGui::Combo("denoiser", &denoise, kDenoiseModes, 3))
    c.settings.denoise = gl::DenoiseMode(denoise);
  bool lensMatched = c.settings.sampleMap == SampleMapKind::LensMatched;
  if (ImGui::Checkbox("lens-matched sampling (hybrid)", &lensMatched))
    c.settings.sampleMap = lensMatched ? SampleMapKind::LensMatched : SampleMapKind::Uniform;
  ImGui::Checkbox("stereo path reuse", &c.settings.stereoReuse);
  ImGui::Checkbox("light-traced caustics", &c.settings.caustics);
  ImGui::Checkbox("re-projection", &c.reproject);
  ImGui::SliderFloat("exposure", &c.exposure, 0.05f, 8.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
  ImGui::TextUnformatted(head.source->status().c_str());
  ImGui::TextUnformatted("F12 saves the panel image");
  ImGui::End();
}

// The GL objects of a session, created once the window's context is current.
struct Session {
  ViewConfig& c;
  std::unique_ptr<gl::Context> context;
  Head head;
  std::unique_ptr<FramePipeline> pipeline;  // frames traced on its background worker
  std::unique_ptr<display::Compositor> compositor;
  std::unique_ptr<ViewOverlay> overlay;
  std::optional<StereoFrame> shown;  // its display textures are what the compositor shows
  int saved = 0;
  Stats stats;
  double sceneClock = hmd::hostSeconds();  // when the scene clock last advanced

  explicit Session(ViewConfig& config) : c(config) {
    head = openHead(c.hmd);  // bad pose files are reported before a window opens
    gl::ContextOptions o;
    o.backend = gl::Backend::GLFW;
    o.windowWidth = c.window.x, o.windowHeight = c.window.y;
    o.visible = true;
    o.title = "photovr view";
    const bool dk2 = c.hmd.kind == "dk2" && !head.desktop;
    if (dk2) placeOnHeadset(o);
    context = gl::Context::create(o);
    if (c.panel.x == 0)
      c.panel = dk2 ? glm::ivec2(c.headset.lens.panel.hResolution, c.headset.lens.panel.vResolution)
                    : glm::ivec2(c.window.x & ~1, c.window.y);
    PipelineConfig p;
    p.layout = c.eyes;
    p.lens = c.headset.lens;
    p.forDisplay = true;
    pipeline = std::make_unique<FramePipeline>(c.scene, p, context.get());
    pipeline->prepare(c.settings);
    if (c.animated) pipeline->animate(c.scene);  // plays on the wall clock
    compositor =
        std::make_unique<display::Compositor>(c.headset, c.eyes, c.panel.x, c.panel.y, c.rotation);
    if (c.overlay) overlay = std::make_unique<ViewOverlay>(*context);
  }

  // The DK2's own monitor, fullscreen and turned for its panel; else a mirror window.
  void placeOnHeadset(gl::ContextOptions& o) {
    const gl::HeadsetMonitor m = gl::pickHeadsetMonitor(gl::listMonitors());
    if (m.index < 0) {
      std::printf("view: DK2 display not found (%s); showing a mirror window\n", m.reason.c_str());
      return;
    }
    std::printf("view: DK2 display is %s; fullscreen there\n", m.reason.c_str());
    o.fullscreenMonitor = m.index;
    if (!c.rotationGiven) c.rotation = m.rotation;
  }

  Pose headPose(double t) { return display::composePose(c.view.head, head.source->pose(t)); }
  std::array<EyeCamera, 2> eyesAt(double t, glm::vec2 jitter) {
    return display::headEyes(headPose(t), c.eyes, jitter, c.headset.ipd);
  }

  // A finished frame (denoised, or uploaded as is, by the pipeline's take()) replaces the
  // one shown, whose images the worker traces a later frame into.
  void accept(StereoFrame f, double finishMs) {
    stats.denoiseMs = finishMs;
    stats.meanSpp = 0.5 * (meanSamples(f.images[0]) + meanSamples(f.images[1]));
    ++stats.rendered;
    stats.last = f.request;
    stats.lastTimes = f.times;
    if (shown) pipeline->recycle(std::move(*shown));
    shown = std::move(f);
  }

  void composite(const glm::ivec2& framebuffer) {
    const auto t0 = Clock::now();
    const auto to = eyesAt(head.now() + c.headset.displayLatency, {});
    compositor->run(shown->display, shown->request.eyes, to, c.exposure, c.reproject);
    display::WindowOutput window([&] { return framebuffer; });  // the DK2's panel, or a mirror
    compositor->show(window, int(shown->request.index));
    gl::waitForGpu();
    stats.compositorMs = msSince(t0);
  }

  void savePanel() {
    char name[48];
    std::snprintf(name, sizeof name, "/photovr-view-%04d.png", saved++);
    const gl::PanelOutput& out = compositor->output();
    writeImage(c.outDir + name, flipToImage(out.read(), out.width(), out.height()));
    std::printf("saved %s%s\n", c.outDir.c_str(), name);
  }
};

int runSession(ViewConfig& c) {
  Session s(c);
  gl::WindowInputReader input(*s.context);
  std::printf("view: %s, %s; eyes %dx%d, panel %dx%d, window %dx%d\n",
              s.context->renderer().c_str(), s.head.source->status().c_str(), c.eyes.width,
              c.eyes.height, c.panel.x, c.panel.y, c.window.x, c.window.y);
  auto last = Clock::now();
  int shownFrames = 0;
  uint32_t started = 0;
  while (!s.context->shouldClose()) {
    const gl::WindowInput in = input.poll();
    if (in.quitPressed) break;
    const double dt = msSince(last);
    last = Clock::now();
    s.stats.displayMs = 0.9 * s.stats.displayMs + 0.1 * dt;
    if (s.head.desktop && !(s.overlay && s.overlay->wantsMouse()))
      s.head.desktop->handle(desktopInput(in, float(dt * 1e-3)));
    const auto tf = Clock::now();
    if (auto f = s.pipeline->take()) {  // finishes it: the denoiser or the upload
      gl::waitForGpu();
      s.accept(std::move(*f), msSince(tf));
    }
    if (!s.pipeline->busy()) {
      const uint32_t index = started++;
      // The scene clock runs in real time while playing, like the head's: a frame shows the
      // scene as it is when the frame starts.
      const double now = hmd::hostSeconds();
      if (c.playing) c.sceneTime += now - s.sceneClock;
      s.sceneClock = now;
      s.pipeline->start({s.eyesAt(s.head.now(), samplePosition(SamplerKind::Sobol, index)), 2,
                         index, c.settings, c.sceneTime});
    }
    if (s.shown) s.composite(in.framebufferSize);
    if (s.overlay) {
      s.overlay->newFrame();
      drawOverlay(c, s.stats, s.head);
      s.overlay->render();
    }
    if (in.savePressed && s.shown) s.savePanel();
    if (s.shown && c.frames && ++shownFrames >= c.frames) {
      if (!c.screenshot.empty()) {
        const glm::ivec2 fb = in.framebufferSize;
        writeImage(c.screenshot, flipToImage(gl::readDefaultFramebuffer(fb.x, fb.y), fb.x, fb.y));
        std::printf("wrote %s\n", c.screenshot.c_str());
      }
      break;
    }
    s.context->swapBuffers();
  }
  std::printf("view: %d frames rendered, last %.0f ms; compositor %.1f ms per refresh\n",
              s.stats.rendered, s.stats.lastTimes.totalMs(), s.stats.compositorMs);
  return 0;
}

}  // namespace

int runView(const Args& args) {
  if (wantsHelp(args)) {
    std::cout << kViewCommandHelp << kHeadHelp;
    return 0;
  }
  ViewConfig config = parseViewConfig(args);
  return runSession(config);
}

}  // namespace photovr::app
