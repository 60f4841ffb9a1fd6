#include "harness/bench_run.h"

#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <functional>
#include <memory>
#include <utility>

#include "core/memory.h"
#include "trace/trace_output.h"
#include "core/error_metrics.h"
#include "core/perceptual_metrics.h"
#include "core/stopwatch.h"
#include "hybrid/frame_pipeline.h"
#include "hmd/headset_description.h"

namespace photovr::harness {
namespace {

FrameSettings settingsOf(const BenchConfig& c) {
  FrameSettings s;
  s.mode = c.mode;
  s.spp = c.spp;
  s.bounces = c.bounces;
  s.sampleMap = c.sampling;
  s.denoise = c.denoise;
  s.stereoReuse = c.stereoReuse;
  return s;
}

// Scores both eyes: relMSE and PSNR over all their pixels, SSIM the mean of the eyes'.
// Pixels a sample map never traces (the lens's hidden area, never shown) take the
// reference's value, so only what the headset shows counts.
void score(FrameRecord& r, const std::array<std::vector<glm::vec3>, 2>& eyes, const BenchScene& s,
           const BenchConfig& c, const StereoSampleMaps& maps) {
  std::vector<glm::vec3> all, ref;
  r.ssim = 0.0;
  for (int e = 0; e < 2; ++e) {
    std::vector<glm::vec3> img = eyes[e];
    for (size_t i = 0; i < img.size(); ++i)
      if (maps[e].skips(i)) img[i] = s.reference[e][i];
    r.ssim += 0.5 * ssimDisplay(img, s.reference[e], c.width, c.height);
    all.insert(all.end(), img.begin(), img.end());
    ref.insert(ref.end(), s.reference[e].begin(), s.reference[e].end());
  }
  r.relMse = relMse(all, ref);
  r.psnr = psnrDisplay(all, ref);
}

// One configuration's frames through the frame pipeline: hybrid (G-buffer, read-back,
// rebuild, trace; optional SVGF) or pt (no GL without the denoiser).
struct Run {
  const BenchConfig& c;
  const View& view;
  FramePipeline pipeline;
  std::array<EyeImage, 2> sums;
  uint64_t rejected = 0;

  static PipelineConfig configOf(const BenchConfig& c) {
    PipelineConfig p;
    p.layout = hmd::HeadsetDescription::dk2().layout(c.width, c.height);
    p.timeDenoiserPasses = true;
    return p;
  }
  static bool needsGl(const BenchConfig& c) {
    return c.mode == FrameMode::Hybrid || c.denoise != gl::DenoiseMode::Off;
  }

  Run(const BenchConfig& cfg, const BenchScene& s, gl::Context& ctx)
      : c(cfg), view(s.view), pipeline(*s.scene, configOf(cfg), needsGl(cfg) ? &ctx : nullptr) {
    pipeline.prepare(settingsOf(cfg));  // the denoiser's set-up is not a frame's
  }

  // Frame f's stage times and rays into 'r'; the frame's wall time is the pipeline's.
  StereoFrame render(uint32_t f, FrameRecord& r) {
    const auto t0 = Clock::now();
    StereoFrame frame = pipeline.render(
        {eyeCameras(view, c.width, c.height, f, SamplerKind::Sobol), 2, f, settingsOf(c)});
    r.frameMs = msSince(t0);
    const FrameTimes& t = frame.times;
    r.gbufferMs = t.gbufferMs, r.readbackMs = t.readbackMs;
    r.rebuildMs = t.rebuildMs, r.traceMs = t.traceMs, r.rays = t.rays;
    r.denoiseMs = t.denoisePassMs;
    r.mraysPerSecond = double(t.rays) / (t.cpuMs() * 1e3);
    rejected += t.rejectedSamples;
    return frame;
  }

  // The image to score after frame f (nothing to read back when the frame is not scored).
  std::array<std::vector<glm::vec3>, 2> shown(const StereoFrame& frame, uint32_t f) {
    if (frame.denoised && !c.scored) return {};
    const gl::Denoiser* d = pipeline.denoiser();
    if (frame.denoised) return {d->readLinear(0), d->readLinear(1)};
    for (int e = 0; e < 2; ++e) accumulate(sums[e], frame.images[e], int(f));
    return {sums[0].color, sums[1].color};
  }
};

// y at x on the straight line through (x0, y0) and (x1, y1) in log-log axes.
double logLogAt(double x, double x0, double y0, double x1, double y1) {
  const double t = (std::log(x) - std::log(x0)) / (std::log(x1) - std::log(x0));
  return std::exp(std::log(y0) + t * (std::log(y1) - std::log(y0)));
}

}  // namespace

ConfigResult runConfig(const BenchConfig& c, const BenchScene& s, gl::Context& context) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  size_t(c.resolvedThreads()));
  ConfigResult result{c, {}, 0.0, 0};
  Run run(c, s, context);
  if (c.scored && c.mode == FrameMode::Hybrid) {  // shaders and first-use allocations, untimed
    FrameRecord warmup;
    run.pipeline.recycle(run.render(0, warmup));
    run.pipeline.resetHistory();
    run.rejected = 0;
  }
  const StereoSampleMaps& maps = run.pipeline.sampleMaps(c.sampling, c.spp);
  double elapsed = 0.0;
  for (int f = 0; f < c.frames; ++f) {
    FrameRecord r;
    r.frames = f + 1;
    StereoFrame frame = run.render(uint32_t(f), r);
    const auto shown = run.shown(frame, uint32_t(f));  // not part of the frame's time
    run.pipeline.recycle(std::move(frame));
    elapsed += r.frameMs;
    r.elapsedMs = elapsed;
    if (c.scored) score(r, shown, s, c, maps);
    result.frames.push_back(r);
  }
  result.rejectedSamples = run.rejected;
  result.peakRssMiB = peakRssMiB();
  return result;
}

double meanOf(const ConfigResult& r, double FrameRecord::*field) {
  double sum = 0;
  for (const FrameRecord& f : r.frames) sum += f.*field;
  return r.frames.empty() ? 0.0 : sum / double(r.frames.size());
}

double timeToError(const std::vector<FrameRecord>& c, double error) {
  if (c.empty()) return std::numeric_limits<double>::infinity();
  for (size_t i = 1; i < c.size(); ++i)
    if (c[i].relMse <= error && c[i - 1].relMse > error)
      return logLogAt(error, c[i - 1].relMse, c[i - 1].elapsedMs, c[i].relMse, c[i].elapsedMs);
  const FrameRecord& end = c.front().relMse <= error ? c.front() : c.back();
  return end.elapsedMs * end.relMse / error;
}

double errorAtTime(const std::vector<FrameRecord>& c, double ms) {
  if (c.empty()) return std::numeric_limits<double>::infinity();
  for (size_t i = 1; i < c.size(); ++i)
    if (c[i].elapsedMs >= ms && c[i - 1].elapsedMs < ms)
      return logLogAt(ms, c[i - 1].elapsedMs, c[i - 1].relMse, c[i].elapsedMs, c[i].relMse);
  const FrameRecord& end = c.front().elapsedMs >= ms ? c.front() : c.back();
  return end.relMse * end.elapsedMs / ms;
}

}  // namespace photovr::harness
