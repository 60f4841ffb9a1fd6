// photovr render --hmd: a sequence rendered at the head poses of a pose source and shown
// through the headset compositor, headless.
//
// Timing model (script time, seconds from the pose source's start; dk2: the host clock):
//   frame k starts rendering at  t_render(k)  = k / fps            (--fps, default 30)
//   and is displayed at          t_display(k) = t_render(k) + L    (--latency-ms L)
// L defaults to one renderer frame (1 / fps): the frame started at t_render(k) is finished
// when frame k + 1 starts, and is shown then. The frame is rendered at the pose of
// t_render(k) (the pose the renderer knew when it started) and re-projected to the pose of
// t_display(k) — what the compositor does with the newest prediction at scan-out. Display
// poses are unjittered; rendered frames carry the Halton jitter of their index.
#include "app/hmd_sequence.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>

#include "gl/render_context.h"
#include "core/memory.h"
#include "core/options.h"
#include "trace/trace_output.h"
#include "core/files.h"
#include "core/error.h"
#include "core/stopwatch.h"
#include "hmd/dk2_driver.h"
#include "display/compositor.h"
#include "display/output.h"
#include "hmd/headset_description.h"
#include "hybrid/frame_pipeline.h"

namespace photovr::app {

const char* const kHmdRenderHelp =
    "headset sequence (renders --frames N frames through the headset compositor):\n"
    "  --hmd sim FILE         head poses from a pose script (CSV t,x,y,z,yaw,pitch,roll;\n"
    "                         seconds, metres, degrees), relative to the scene camera\n"
    "  --hmd replay FILE      orientation from a recorded DK2 HID stream (hmd/recording.h)\n"
    "  --hmd dk2              a DK2 over hidapi;  --hmd none: a plain render (default)\n"
    "  --fps F                renderer rate: frame k is rendered at the pose of t = k / F\n"
    "                         (default 30)\n"
    "  --latency-ms L         and re-projected to the pose of t + L (default 1000 / F)\n"
    "  --panel WxH            panel pixels (default 1920x1080, the DK2's)\n"
    "  --rotate 0|90|180|270  panel output rotation (default 0; the DK2 scans at 90)\n"
    "  --overscan DEG         render the eyes DEG beyond the lens's field on every side (0..10,\n"
    "                         default 0): a head turn of up to DEG re-projects without a\n"
    "                         black edge; the eye images grow to keep --width x --height\n"
    "                         over the lens's field\n"
    "  writes per frame NNNN_left.png, NNNN_right.png (undistorted, as rendered) and\n"
    "  NNNN_panel.png (re-projected, distorted), and hmd_frames.csv (times, poses,\n"
    "  disoccluded and uncovered fractions)\n";

namespace {

// Pulls "--name value" out of 'args' into 'taken'; given twice is an error (as for --hmd).
void takeOption(Args& args, const std::string& name, Args& taken) {
  bool found = false;
  for (size_t i = 0; i < args.size();) {
    if (args[i] != name) {
      ++i;
      continue;
    }
    if (found) throw UsageError(name + ": given twice");
    if (i + 1 >= args.size()) throw UsageError(name + ": missing value");
    taken.insert(taken.end(), {args[i], args[i + 1]});
    args.erase(args.begin() + long(i), args.begin() + long(i) + 2);
    found = true;
  }
}

glm::ivec2 parsePanelSize(const std::string& text) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x')
    throw UsageError("--panel: '" + text + "' is not WIDTHxHEIGHT");
  if (w < 2 || w > 8192 || w % 2 || h < 1 || h > 8192)
    throw UsageError("--panel: " + text + " needs an even width in [2, 8192], height in [1, 8192]");
  return {w, h};
}

std::string eyeImageName(const RenderRequest& r, int k, const char* what) {
  char name[32];
  std::snprintf(name, sizeof name, "/%04d_%s.png", k, what);
  return r.outDir + name;
}

// The pose source's clock for frame k (see the timing model above).
struct FrameTimes {
  double render, display;
  double sinceStart;  // render time less frame 0's
};

}  // namespace

HmdSequenceOptions extractHmdSequenceOptions(Args& args, const HmdSpec& hmd) {
  Args taken;
  const std::set<std::string> names = {"--fps", "--latency-ms", "--rotate", "--panel",
                                       "--overscan"};
  for (const std::string& name : names) takeOption(args, name, taken);
  HmdSequenceOptions o;
  if (taken.empty()) return o;
  if (hmd.kind == "none") throw UsageError(taken[0] + ": needs --hmd sim|replay|dk2");
  const Options opts(taken, names, {});
  o.fps = opts.number("--fps", 30.0f, 0.1f, 1000.0f);
  o.latencyMs = opts.number("--latency-ms", -1.0f, 0.0f, 10000.0f);
  o.rotation = std::stoi(opts.choice("--rotate", "0", {"0", "90", "180", "270"}));
  o.overscanDeg = opts.number("--overscan", 0.0f, 0.0f, 10.0f);
  if (opts.has("--panel")) {
    const glm::ivec2 p = parsePanelSize(opts.text("--panel", ""));
    o.panelWidth = p.x, o.panelHeight = p.y;
  }
  return o;
}

namespace {

// hmd_frames.csv, kept in memory and written complete at the end (core/files.h),
// like every image.
class FrameLog {
 public:
  explicit FrameLog(const std::string& dir) : path_(dir + "/hmd_frames.csv") {
    out_ << "frame,t_render,t_display,rotation_delta_deg,move_delta_m,disoccluded_left,"
            "disoccluded_right,render_ms,compositor_ms,uncovered_left,uncovered_right\n";
  }
  std::ostream& row() { return out_; }
  void close() { writeFileAtomically(path_, out_.str()); }

 private:
  std::string path_;
  std::ostringstream out_;
};

// One sequence on one context: the frame pipeline, the compositor, the panel images.
class HmdSequence {
 public:
  HmdSequence(RenderRequest& r, const HmdSequenceOptions& o, const hmd::HeadsetDescription& headset)
      : r_(r),
        headset_(headset),
        eyes_(headset.layout(r.width, r.height, float(glm::radians(o.overscanDeg)))),
        context_(gl::createRenderContext(r.backend)),
        pipeline_(r.scene, pipelineConfig(r, eyes_, headset), context_.get()),
        compositor_(headset, eyes_, o.panelWidth, o.panelHeight, o.rotation),
        panelFiles_(r.outDir),
        log_(r.outDir) {
    pipeline_.prepare(frameSettingsOf(r));  // as before: set up before the first frame
    if (isAnimated(r.scene)) pipeline_.animate(r.scene);  // plays on the sequence's clock
  }

  // Frame k rendered with 'trackedA' and shown at 'trackedB' (poses relative to the view).
  void frame(int k, const FrameTimes& t, const Pose& trackedA, const Pose& trackedB) {
    const auto from = display::headEyes(display::composePose(r_.view.head, trackedA), eyes_,
                                        samplePosition(r_.sampler, uint32_t(k)), headset_.ipd);
    const auto to = display::headEyes(display::composePose(r_.view.head, trackedB), eyes_,
                                      glm::vec2(0), headset_.ipd);
    const auto tr = Clock::now();
    // The scene clock runs with the pose source's from --time: frame k shows the scene as
    // it is when the frame starts rendering.
    StereoFrame frame =
        pipeline_.render({from, 2, uint32_t(k), frameSettingsOf(r_), r_.time + t.sinceStart});
    gl::waitForGpu();
    const double renderMs = msSince(tr);
    const auto tc = Clock::now();
    compositor_.run(frame.display, from, to, r_.exposure);
    gl::waitForGpu();
    const double compositorMs = msSince(tc);
    renderTotal_ += renderMs, compositorTotal_ += compositorMs;
    writeImages(k, frame);
    const float turn = glm::degrees(
        glm::angle(glm::normalize(glm::inverse(trackedA.orientation) * trackedB.orientation)));
    log_.row() << k << ',' << t.render << ',' << t.display << ',' << turn << ','
               << glm::length(trackedB.position - trackedA.position) << ','
               << compositor_.timewarp().stats(0).disoccludedFraction() << ','
               << compositor_.timewarp().stats(1).disoccludedFraction() << ',' << renderMs << ','
               << compositorMs << ',' << uncoveredFraction(0) << ',' << uncoveredFraction(1)
               << '\n';
    pipeline_.recycle(std::move(frame));
  }

  // The share of an eye's lens-visible pixels the frame holds nothing for (the strip a
  // turn brings in beyond the buffer; overscan covers it): disoccluded less the filled.
  double uncoveredFraction(int eye) const {
    const gl::ReprojectStats s = compositor_.timewarp().stats(eye);
    const int n = s.reprojected + s.filled + s.uncovered;
    return n ? double(s.uncovered) / n : 0.0;
  }

  void finish(const HmdSequenceOptions& o) {
    log_.close();
    const double n = r_.frames;
    std::printf(
        "%d frames %dx%d per eye (overscan %.3g deg) -> panel %dx%d (rotation %d): render %.1f "
        "ms/frame (denoise %s), compositor (re-projection + distortion + output) %.1f "
        "ms/frame\nwrote %s/NNNN_{left,right,panel}.png and %s/hmd_frames.csv\n",
        r_.frames, eyes_.width, eyes_.height, o.overscanDeg, o.panelWidth, o.panelHeight,
        o.rotation, renderTotal_ / n, gl::denoiseModeName(r_.denoise).c_str(), compositorTotal_ / n,
        r_.outDir.c_str(), r_.outDir.c_str());
  }

 private:
  static PipelineConfig pipelineConfig(const RenderRequest& r, const StereoLayout& eyes,
                                       const hmd::HeadsetDescription& headset) {
    PipelineConfig c;
    c.layout = eyes;
    c.lens = headset.lens;
    c.skips = r.skips;
    c.denoiser.exposure = r.exposure;
    c.forDisplay = true;
    return c;
  }

  void writeImages(int k, const StereoFrame& frame) {
    for (int e = 0; e < 2; ++e) {
      const char* eye = e == 0 ? "left" : "right";
      if (frame.denoised)
        writeImage(eyeImageName(r_, k, eye),
                   flipToImage(pipeline_.denoiser()->readDisplay(e), eyes_.width, eyes_.height));
      else
        writeImage(eyeImageName(r_, k, eye), sideBySide({&frame.images[e]}, r_.exposure));
    }
    compositor_.show(panelFiles_, k);
  }

  const RenderRequest& r_;
  const hmd::HeadsetDescription& headset_;
  StereoLayout eyes_;
  std::unique_ptr<gl::Context> context_;
  FramePipeline pipeline_;
  display::Compositor compositor_;
  display::ImageFileOutput panelFiles_;
  FrameLog log_;
  double renderTotal_ = 0.0, compositorTotal_ = 0.0;
};

}  // namespace

int renderHmdSequence(RenderRequest& r, const HmdSpec& spec, HmdSequenceOptions o) {
  const hmd::HeadsetDescription headset = hmd::HeadsetDescription::dk2();
  if (o.panelWidth == 0)
    o.panelWidth = headset.lens.panel.hResolution, o.panelHeight = headset.lens.panel.vResolution;
  if (r.mode != RenderMode::Hybrid) throw UsageError("--hmd: needs --mode hybrid");
  if (!r.view.stereo) throw UsageError("--hmd: needs --eyes stereo");
  std::string why;
  const auto source = openHeadPoseSource(spec, false, &why);
  if (!source) throw InputError("--hmd dk2", why);
  const double latency = o.latencyMs >= 0.0 ? o.latencyMs * 1e-3 : 1.0 / o.fps;
  const StereoLayout eyes = headset.layout(r.width, r.height, float(glm::radians(o.overscanDeg)));
  checkFrameFitsInMemory(eyes.width, eyes.height, "--width/--height with --overscan");
  HmdSequence sequence(r, o, headset);
  std::printf("hmd: %s; timing: frame k rendered at t = k / %.3g s, shown at t + %.1f ms\n",
              source->status().c_str(), o.fps, latency * 1e3);
  const double start = spec.kind == "dk2" ? hmd::hostSeconds() : 0.0;
  for (int k = 0; k < r.frames; ++k) {
    const double t0 = spec.kind == "dk2" ? hmd::hostSeconds() : k / o.fps;
    const FrameTimes t{t0, t0 + latency, t0 - start};
    sequence.frame(k, t, source->pose(t.render), source->pose(t.display));
  }
  sequence.finish(o);
  return 0;
}

}  // namespace photovr::app
