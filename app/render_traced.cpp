// photovr render --mode hybrid|pt: frames accumulated with sub-pixel jitter, both eyes.
#include <chrono>
#include <cstdio>
#include <functional>
#include <limits>
#include <utility>

#include "gl/render_context.h"
#include "app/render_request.h"
#include "trace/trace_output.h"
#include "hmd/headset_description.h"
#include "hybrid/frame_pipeline.h"
#include "trace/caustics.h"
#include "trace/convergence.h"

namespace photovr::app {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

using FrameRenderer = std::function<StereoFrame(const std::array<EyeCamera, 2>&, uint32_t)>;
// Takes a frame back once it is accumulated (FramePipeline::recycle).
using FrameRecycler = std::function<void(StereoFrame&&)>;

// Renders r.frames frames (jitter from the frame index) and returns the per-eye means; with
// r.converge > 0 it stops as soon as the estimated relMSE of the mean drops below it (the
// view is static, so later frames would only refine a converged image).
std::vector<EyeImage> accumulateFrames(const RenderRequest& r, const FrameRenderer& renderFrame,
                                       int& framesDone, const FrameRecycler& recycle) {
  const int eyeCount = r.view.stereo ? 2 : 1;
  std::vector<EyeImage> sums(eyeCount);
  ConvergenceMonitor monitor;
  const auto t0 = Clock::now();
  uint64_t rays = 0;
  for (framesDone = 0; framesDone < r.frames;) {
    const int f = framesDone;
    StereoFrame frame =
        renderFrame(eyeCameras(r.view, r.width, r.height, uint32_t(f), r.sampler), uint32_t(f));
    for (int e = 0; e < eyeCount; ++e) {
      rays += frame.images[e].rays;
      accumulate(sums[e], frame.images[e], f);
      if (r.converge > 0.0) monitor.add(e, frame.images[e].color, r.width);
    }
    recycle(std::move(frame));
    ++framesDone;
    const double done = double(framesDone) / r.frames, elapsed = secondsSince(t0);
    reportProgress(done, rays / elapsed, elapsed * (1.0 - done) / done);
    if (r.converge > 0.0 && monitor.converged(r.converge)) {
      std::printf("converged after %d frames (estimated relMSE %.2e < %.2e): tracing stopped\n",
                  framesDone, monitor.estimatedRelMse(), r.converge);
      break;
    }
  }
  return sums;
}

void writeAndReport(const RenderRequest& r, const std::vector<EyeImage>& eyes, int frames,
                    double seconds, const std::string& stages) {
  std::vector<OutputFile> files;
  std::vector<const EyeImage*> ptrs;
  uint64_t rays = 0, rejected = 0;
  for (size_t e = 0; e < eyes.size(); ++e) {
    for (OutputFile& f : eyeImageFiles(eyes[e], r.outDir + "/" + eyeFolder(r.view, int(e))))
      files.push_back(std::move(f));
    ptrs.push_back(&eyes[e]);
    rays += eyes[e].rays;
    rejected += eyes[e].rejectedSamples;
  }
  files.push_back({r.outDir + "/color.png", [&](const std::string& path) {
                     writeImage(path, sideBySide(ptrs, r.exposure));
                   }});
  writeFiles(files);
  std::printf("scene %s: %zu triangles, %s\n", r.sceneSpec.c_str(),
              r.scene.instancedTriangleCount(), r.view.description.c_str());
  std::printf(
      "%s %dx%d x %zu eyes, %d spp x %d frames, %d bounces: %.2f s, %.2f Mrays/s, "
      "%llu samples rejected (NaN/Inf)\n",
      renderModeName(r.mode), r.width, r.height, eyes.size(), r.spp, frames, r.bounces, seconds,
      rays / seconds * 1e-6, (unsigned long long)rejected);
  std::printf("stages per frame: %s\nwrote:\n", stages.c_str());
  for (const OutputFile& f : files) std::printf("  %s\n", f.path.c_str());
}

// The denoiser's last frame: denoised.png (both eyes) and per eye denoised.exr (linear).
void writeDenoised(const RenderRequest& r, const gl::Denoiser& denoiser, int eyeCount) {
  // Read from GL here, on its thread; written concurrently (writeFiles).
  Image8 display(r.width * eyeCount, r.height, 3);
  std::vector<std::vector<glm::vec3>> linear(static_cast<size_t>(eyeCount));
  std::vector<OutputFile> files;
  for (int e = 0; e < eyeCount; ++e) {
    const std::vector<glm::u8vec4> d = denoiser.readDisplay(e);
    for (int y = 0; y < r.height; ++y)
      for (int x = 0; x < r.width; ++x) {
        const glm::u8vec4 c = d[size_t(r.height - 1 - y) * r.width + x];
        uint8_t* p = display.at(e * r.width + x, y);
        p[0] = c.r, p[1] = c.g, p[2] = c.b;
      }
    linear[size_t(e)] = denoiser.readLinear(e);
    files.push_back({r.outDir + "/" + eyeFolder(r.view, e) + "/denoised.exr",
                     [&r, &eye = linear[size_t(e)]](const std::string& path) {
                       writeImage(path, toImage(eye, r.width, r.height));
                     }});
  }
  files.push_back({r.outDir + "/denoised.png",
                   [&display](const std::string& path) { writeImage(path, display); }});
  writeFiles(files);
  for (const OutputFile& f : files) std::printf("  %s\n", f.path.c_str());
}

// Both eyes' tracer times: with stereo reuse, that of the eye traced first and of the
// second, which reuses its paths (the eyes take turns), and the second's share of reused paths.
std::string eyeTracerLine(const RenderRequest& r, const FrameTimes& t, double n) {
  if (!r.view.stereo) return "";
  char line[200];
  if (!r.stereoReuse) {
    std::snprintf(line, sizeof line, "; tracer left %.1f ms, right %.1f ms", t.turnTraceMs[0] / n,
                  t.turnTraceMs[1] / n);
    return line;
  }
  const double reused = double(t.turnReusedPaths[1]);
  std::snprintf(line, sizeof line,
                "; tracer first eye %.1f ms, second %.1f ms (stereo reuse, the eyes taking "
                "turns: %.1f %% of the second's paths from the first, %.1f %% of those with "
                "an own bounce)",
                t.turnTraceMs[0] / n, t.turnTraceMs[1] / n,
                t.turnPaths[1] ? 100.0 * reused / double(t.turnPaths[1]) : 0.0,
                reused > 0 ? 100.0 * double(t.turnOwnBounces[1]) / reused : 0.0);
  return line;
}

// The stage line of the report, per frame.
std::string stageLine(const RenderRequest& r, const FrameTimes& total, int frames, double buildMs) {
  const double n = frames;
  const std::string name = gl::denoiseModeName(r.denoise);
  const char* denoise = name.c_str();
  char stages[320];
  if (r.mode == RenderMode::PathTraced)
    std::snprintf(stages, sizeof stages,
                  "BVH build %.0f ms (once), trace %.1f ms, denoise (%s) %.1f ms", buildMs,
                  total.traceMs / n, denoise, total.denoiseMs / n);
  else
    std::snprintf(stages, sizeof stages,
                  "G-buffer %.1f ms, read-back %.1f ms, hit rebuild %.1f ms, trace %.1f ms, "
                  "denoise (%s) %.1f ms (%llu shared-edge hits clamped)",
                  total.gbufferMs / n, total.readbackMs / n, total.rebuildMs / n, total.traceMs / n,
                  denoise, total.denoiseMs / n, (unsigned long long)total.outsideHits);
  std::string line = stages + eyeTracerLine(r, total, n);
  if (total.animateMs > 0.0) {
    std::snprintf(stages, sizeof stages, "; posing the scene %.2f ms", total.animateMs / n);
    line += stages;
  }
  if (r.caustics && hasLightTracedCaustics(r.scene)) {  // nothing to say where none are traced
    std::snprintf(stages, sizeof stages,
                  "; light-traced caustics %.1f ms of the tracer's (first eye %.1f, second "
                  "%.1f), %.0f connections of light paths a frame landed on a pixel",
                  (total.turnCausticMs[0] + total.turnCausticMs[1]) / n, total.turnCausticMs[0] / n,
                  total.turnCausticMs[1] / n, double(total.causticSplats) / n);
    line += stages;
  }
  return line;
}

}  // namespace

FrameSettings frameSettingsOf(const RenderRequest& r) {
  FrameSettings s;
  s.mode = r.mode == RenderMode::PathTraced ? FrameMode::PathTraced : FrameMode::Hybrid;
  s.spp = r.spp;
  s.bounces = r.bounces;
  s.seed = r.seed;
  s.sampler = r.sampler;
  s.sampleMap = r.sampling;
  s.denoise = r.denoise;
  s.stereoReuse = r.stereoReuse;
  s.caustics = r.caustics;
  return s;
}

int renderTracedMode(RenderRequest& r) {
  const FrameSettings settings = frameSettingsOf(r);
  // pt without the denoiser needs no GL at all; the denoiser's guides are a G-buffer.
  std::unique_ptr<gl::Context> context;
  if (settings.mode == FrameMode::Hybrid || settings.denoise != gl::DenoiseMode::Off)
    context = gl::createRenderContext(r.backend);
  PipelineConfig config;
  config.layout = hmd::HeadsetDescription::dk2().layout(r.width, r.height);
  config.skips = r.skips;
  config.denoiser.exposure = r.exposure;
  const auto t0 = Clock::now();
  FramePipeline pipeline(r.scene, config, context.get());
  pipeline.prepare(settings);  // the denoiser's set-up is not a frame's
  if (r.play && isAnimated(r.scene)) pipeline.animate(r.scene);
  const double buildMs = 1e3 * secondsSince(t0);
  if (settings.mode == FrameMode::Hybrid)
    std::printf("sampling: %s (%s)\n", sampleMapKindName(r.sampling),
                describeSampleMaps(pipeline.sampleMaps(r.sampling, r.spp)).c_str());
  const int eyeCount = r.view.stereo ? 2 : 1;
  FrameTimes total;
  const auto t1 = Clock::now();
  int frames = 0;
  const auto sums = accumulateFrames(
      r,
      [&](const std::array<EyeCamera, 2>& eyes, uint32_t f) {
        const double sceneTime =
            r.play ? r.time + f * kAnimationFrameSeconds : std::numeric_limits<double>::quiet_NaN();
        StereoFrame frame = pipeline.render({eyes, eyeCount, f, settings, sceneTime});
        total.add(frame.times);
        return frame;
      },
      frames, [&](StereoFrame&& frame) { pipeline.recycle(std::move(frame)); });
  writeAndReport(r, sums, frames, secondsSince(t1), stageLine(r, total, frames, buildMs));
  if (pipeline.denoiser()) writeDenoised(r, *pipeline.denoiser(), eyeCount);
  return 0;
}

}  // namespace photovr::app
