#include "app/bench_run.h"

#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <functional>
#include <memory>
#include <utility>

#include "app/memory.h"
#include "app/sample_maps.h"
#include "app/trace_output.h"
#include "core/error_metrics.h"
#include "core/perceptual_metrics.h"
#include "core/stopwatch.h"
#include "hybrid/denoise_input.h"
#include "hybrid/hybrid_renderer.h"

namespace photovr::app {
namespace {

using Eyes = std::array<EyeImage, 2>;

TraceSettings settingsOf(const BenchConfig& c) {
  TraceSettings s;
  s.samplesPerPixel = c.spp;
  s.maxBounces = c.bounces;
  return s;
}

// Scores both eyes: relMSE and PSNR over all their pixels, SSIM the mean of the eyes'.
// Pixels a sample map never traces (the lens's hidden area, never shown) take the
// reference's value, so only what the headset shows counts.
void score(FrameRecord& r, const std::array<std::vector<glm::vec3>, 2>& eyes, const BenchScene& s,
           const BenchConfig& c, const std::array<std::vector<uint16_t>, 2>& maps) {
  std::vector<glm::vec3> all, ref;
  r.ssim = 0.0;
  for (int e = 0; e < 2; ++e) {
    std::vector<glm::vec3> img = eyes[e];
    if (!maps[e].empty())
      for (size_t i = 0; i < img.size(); ++i)
        if (maps[e][i] == 0) img[i] = s.reference[e][i];
    r.ssim += 0.5 * ssimDisplay(img, s.reference[e], c.width, c.height);
    all.insert(all.end(), img.begin(), img.end());
    ref.insert(ref.end(), s.reference[e].begin(), s.reference[e].end());
  }
  r.relMse = relMse(all, ref);
  r.psnr = psnrDisplay(all, ref);
}

// Renders frame f into 'r' (stage times, rays) and returns the image to score after it.
using FrameFn = std::function<std::array<std::vector<glm::vec3>, 2>(uint32_t f, FrameRecord& r)>;

// Hybrid: G-buffer, read-back, rebuild, trace; optional SVGF on the result.
struct HybridRun {
  HybridRenderer renderer;
  std::unique_ptr<gl::Denoiser> denoiser;
  std::array<std::vector<uint16_t>, 2> maps;
  std::array<EyeImage, 2> sums;
  const BenchConfig& c;
  const View& view;
  uint64_t rejected = 0;

  HybridRun(const BenchConfig& cfg, const BenchScene& s, gl::Context& ctx)
      : renderer(*s.scene, cfg.width, cfg.height,
                 ctx.hasExtension("GL_ARB_shader_viewport_layer_array"), settingsOf(cfg)),
        maps(lensSampleMaps(cfg.sampling, StereoLayout::dk2(cfg.width, cfg.height), cfg.spp)),
        c(cfg),
        view(s.view) {
    if (cfg.denoise != gl::DenoiseMode::Off) {
      denoiser = std::make_unique<gl::Denoiser>(cfg.width, cfg.height);
      denoiser->setTiming(true);
    }
  }

  Eyes render(uint32_t f, FrameRecord& r) {
    HybridFrameTimes t;
    Eyes out = renderer.render(
        eyeCameras(view, c.width, c.height, f, SamplerKind::Sobol), 2, f, &t,
        {maps[0].empty() ? nullptr : &maps[0], maps[1].empty() ? nullptr : &maps[1]});
    r.gbufferMs = t.gbufferMs, r.readbackMs = t.readbackMs;
    r.rebuildMs = t.rebuildMs, r.traceMs = t.traceMs, r.rays = t.rays;
    r.mraysPerSecond = double(t.rays) / (t.cpuMs() * 1e3);
    rejected += t.rejectedSamples;
    if (denoiser) {
      const DenoiseInput left = makeDenoiseInput(out[0]), right = makeDenoiseInput(out[1]);
      denoiser->run(renderer.gbuffer(), {left.eye, right.eye}, 2, c.denoise, f == 0);
      for (const gl::PassTiming& p : denoiser->timings()) r.denoiseMs += p.ms;
    }
    return out;
  }

  // The image to score after frame f (nothing to read back when the frame is not scored).
  std::array<std::vector<glm::vec3>, 2> shown(const Eyes& out, uint32_t f) {
    if (denoiser && !c.scored) return {};
    if (denoiser) return {denoiser->readLinear(0), denoiser->readLinear(1)};
    for (int e = 0; e < 2; ++e) accumulate(sums[e], out[e], int(f));
    return {sums[0].color, sums[1].color};
  }
};

struct PathTracedRun {
  EmbreeScene embree;
  LightSet lights;
  TraceContext ctx;
  std::array<EyeImage, 2> sums;
  Eyes last;  // the previous frame's, traced into (as the hybrid reuses its storage)
  const BenchConfig& c;
  const View& view;
  uint64_t rejected = 0;

  PathTracedRun(const BenchConfig& cfg, const BenchScene& s)
      : embree(*s.scene),
        lights(*s.scene),
        ctx{*s.scene, embree, lights, settingsOf(cfg)},
        c(cfg),
        view(s.view) {}

  std::array<std::vector<glm::vec3>, 2> frame(uint32_t f, FrameRecord& r) {
    const auto cams = eyeCameras(view, c.width, c.height, f, SamplerKind::Sobol);
    const auto t0 = Clock::now();
    Eyes& out = last;
    for (int e = 0; e < 2; ++e)
      out[e] = renderPathTraced(ctx, cams[e], uint32_t(e), f, std::move(out[e]));
    r.traceMs = r.frameMs = msSince(t0);
    r.rays = out[0].rays + out[1].rays;
    r.mraysPerSecond = double(r.rays) / (r.traceMs * 1e3);
    rejected += out[0].rejectedSamples + out[1].rejectedSamples;
    for (int e = 0; e < 2; ++e) accumulate(sums[e], out[e], int(f));
    return {sums[0].color, sums[1].color};
  }
};

// y at x on the straight line through (x0, y0) and (x1, y1) in log-log axes.
double logLogAt(double x, double x0, double y0, double x1, double y1) {
  const double t = (std::log(x) - std::log(x0)) / (std::log(x1) - std::log(x0));
  return std::exp(std::log(y0) + t * (std::log(y1) - std::log(y0)));
}

// The frame loop shared by both modes. The frame function sets the frame's time: the
// accumulation and read-back for scoring are not part of a frame.
std::vector<FrameRecord> runFrames(const BenchConfig& c, const BenchScene& s, const FrameFn& frame,
                                   const std::array<std::vector<uint16_t>, 2>& maps) {
  std::vector<FrameRecord> records;
  double elapsed = 0.0;
  for (int f = 0; f < c.frames; ++f) {
    FrameRecord r;
    r.frames = f + 1;
    const auto shown = frame(uint32_t(f), r);
    elapsed += r.frameMs;
    r.elapsedMs = elapsed;
    if (c.scored) score(r, shown, s, c, maps);
    records.push_back(r);
  }
  return records;
}

}  // namespace

ConfigResult runConfig(const BenchConfig& c, const BenchScene& s, gl::Context& context) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  size_t(c.resolvedThreads()));
  ConfigResult result{c, {}, 0.0, 0};
  if (c.mode == "pt") {
    PathTracedRun run(c, s);
    result.frames =
        runFrames(c, s, [&](uint32_t f, FrameRecord& r) { return run.frame(f, r); }, {});
    result.rejectedSamples = run.rejected;
  } else {
    HybridRun run(c, s, context);
    if (c.scored) {  // shader compilation and first-use allocations, not timed
      FrameRecord warmup;
      run.render(0, warmup);
      run.rejected = 0;
    }
    result.frames = runFrames(
        c, s,
        [&](uint32_t f, FrameRecord& r) {
          const auto t0 = Clock::now();
          Eyes out = run.render(f, r);
          r.frameMs = msSince(t0);
          auto shown = run.shown(out, f);
          run.renderer.recycle(std::move(out));
          return shown;
        },
        run.maps);
    result.rejectedSamples = run.rejected;
  }
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

}  // namespace photovr::app
