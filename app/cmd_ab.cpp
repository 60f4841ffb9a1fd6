// photovr ab: hybrid against pure path tracing at equal settings, both judged against a
// cached converged reference; photovr reference: build or extend that reference.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <utility>

#include "gl/render_context.h"
#include "core/files.h"
#include "core/options.h"
#include "harness/reference_cache.h"
#include "app/render_request.h"
#include "trace/trace_output.h"
#include "core/error.h"
#include "core/error_metrics.h"
#include "core/heatmap.h"
#include "core/scene_transform.h"
#include "core/stopwatch.h"
#include "hmd/headset_description.h"
#include "hybrid/frame_pipeline.h"
#include "trace/primary_rays.h"

namespace photovr::app {
namespace {

using harness::loadOrRenderReference;
using harness::parseShard;
using harness::Reference;
using harness::ReferenceSpec;
using harness::renderReferenceShard;
using harness::ShardId;
using harness::ShardResult;

const char* const kAbHelp =
    "usage: photovr ab [options]\n"
    "Renders the same frames in hybrid and pure path-traced mode, compares both with a\n"
    "converged reference (cached, see `photovr reference`) and writes hybrid.png, pt.png,\n"
    "reference.png, heatmap.png (relMSE per pixel) and summary.txt into --out.\n"
    "  --scene NAME|FILE      default atrium\n"
    "  --width W --height H   per-eye size (default 240x270, a quarter of the DK2's eye)\n"
    "  --spp N --frames F --bounces N --seed S   as for render (defaults 1, 1, 8, 0)\n"
    "  --reference-spp N      reference samples per pixel (default 256)\n"
    "  --stereo-reuse on|off  as for render (default on), both modes\n"
    "  --caustics on|off      as for render (default on), both modes\n"
    "  --backend B --exposure E --env FILE --out DIR (default out/ab-<scene>)\n";

const char* const kReferenceHelp =
    "usage: photovr reference [options]\n"
    "Renders (or extends) the converged path-traced reference of a scene and view into the\n"
    "cache ($PHOTOVR_CACHE_DIR or ~/.cache/photovr), keyed by scene content and settings.\n"
    "Stopping and re-running continues without losing samples.\n"
    "  --scene NAME|FILE --width W --height H --bounces N --env FILE  (as for ab)\n"
    "  --spp N                total samples per pixel wanted (default 256)\n"
    "  --shard K/N            render only shard K of N (frames K, K+N, ...), as one job of\n"
    "                         N (scripts/cluster/); the job that completes the set merges\n"
    "                         them into the reference, bit for bit the unsharded one\n";

struct AbRequest {
  RenderRequest render;
  int referenceSpp = 256;
  std::optional<ShardId> shard;  // reference --shard K/N
};

AbRequest parseAb(const Args& args, bool referenceOnly) {
  std::set<std::string> valued = {"--scene",         "--env",     "--width",    "--height",
                                  "--spp",           "--frames",  "--bounces",  "--seed",
                                  "--reference-spp", "--backend", "--exposure", "--out"};
  if (!referenceOnly) valued.insert({"--stereo-reuse", "--caustics"});
  if (referenceOnly) valued.insert("--shard");
  valued.insert(kViewOptions.begin(), kViewOptions.end());
  const Options o(args, valued, {});
  if (!o.positional().empty()) throw UsageError("unexpected argument '" + o.positional()[0] + "'");
  AbRequest a;
  RenderRequest& r = a.render;
  r.sceneSpec = o.text("--scene", "atrium");
  r.width = o.integer("--width", 240, 1, 8192);
  r.height = o.integer("--height", 270, 1, 8192);
  r.spp = o.integer("--spp", referenceOnly ? 256 : 1, 1, 1 << 20);
  r.frames = o.integer("--frames", 1, 1, 65536);
  r.bounces = o.integer("--bounces", 8, 0, 64);
  r.seed = uint32_t(o.integer("--seed", 0, 0, 2147483647));
  r.exposure = o.number("--exposure", 1.0f, 1e-6f, 1e6f);
  r.backend = o.text("--backend", "");
  a.referenceSpp = o.integer("--reference-spp", 256, 1, 1 << 20);
  if (o.has("--shard")) a.shard = parseShard(o.text("--shard", ""));
  r.stereoReuse = parseStereoReuse(o);
  r.caustics = parseCaustics(o);
  const std::string stem = r.sceneSpec.substr(r.sceneSpec.find_last_of('/') + 1);
  r.outDir = o.text("--out", "out/ab-" + stem.substr(0, stem.find('.')));
  createOutputFolder(r.outDir);
  r.scene = loadSceneSpec(r.sceneSpec);
  applyEnvironmentOption(r.scene, o.text("--env", ""));
  applyTimeOption(r.scene, o);
  warnAboutScene(r.scene);
  r.view = resolveView(r.scene, o);
  r.view.head = recenterOnView(r.scene, r.view.head);  // camera-relative: full precision
  return a;
}

// A 4-frame sequence rendered both ways: sequential (synchronous read-back) and pipelined
// (frame N + 1's G-buffer and PBO read-back queued before frame N is traced).
struct PipelineTimes {
  double sequentialMs = 0.0, pipelinedMs = 0.0, waitMs = 0.0;
};

FrameRequest requestOf(const RenderRequest& r, int eyeCount, uint32_t f, FrameMode mode) {
  FrameRequest q{eyeCameras(r.view, r.width, r.height, f, r.sampler), eyeCount, f,
                 frameSettingsOf(r)};
  q.settings.mode = mode;
  return q;
}

PipelineTimes measurePipeline(FramePipeline& pipeline, const RenderRequest& r, int eyeCount) {
  PipelineTimes p;
  auto requests = [&](uint32_t f) { return requestOf(r, eyeCount, f, FrameMode::Hybrid); };
  for (int pipelined = 0; pipelined < 2; ++pipelined) {
    FrameTimes t;
    const auto t0 = Clock::now();
    pipeline.renderSequence(
        requests, 4,
        pipelined ? FramePipeline::Scheduling::Pipelined : FramePipeline::Scheduling::Sequential,
        [](StereoFrame&) {}, &t);
    (pipelined ? p.pipelinedMs : p.sequentialMs) = msSince(t0);
    if (pipelined) p.waitMs = t.gbufferMs;
  }
  return p;
}

struct ModeResult {
  std::vector<EyeImage> eyes;
  double wallMs = 0.0, cpuMs = 0.0, primaryMs = 0.0;
  FrameTimes stages;
  uint64_t rays = 0;
  double relMse = 0.0, psnr = 0.0;
};

ModeResult runHybrid(FramePipeline& pipeline, const RenderRequest& r, int eyeCount) {
  ModeResult m;
  m.eyes.resize(eyeCount);
  // Warm-up: shader compilation, and the first touch of the storage every frame reuses.
  pipeline.recycle(pipeline.render(requestOf(r, eyeCount, 0, FrameMode::Hybrid)));
  for (int f = 0; f < r.frames; ++f) {
    StereoFrame frame = pipeline.render(requestOf(r, eyeCount, uint32_t(f), FrameMode::Hybrid));
    for (int e = 0; e < eyeCount; ++e) accumulate(m.eyes[e], frame.images[e], f);
    m.stages.add(frame.times);
    m.rays += frame.times.rays;
    pipeline.recycle(std::move(frame));
  }
  m.wallMs = m.stages.totalMs();
  m.cpuMs = m.stages.cpuMs();
  return m;
}

ModeResult runPathTraced(FramePipeline& pipeline, const RenderRequest& r, int eyeCount) {
  ModeResult m;
  m.eyes.resize(eyeCount);
  const TraceContext& ctx = pipeline.traceContext();
  // Warm-up, as the hybrid's: the first touch of the storage every frame is traced into.
  pipeline.recycle(pipeline.render(requestOf(r, eyeCount, 0, FrameMode::PathTraced)));
  for (int f = 0; f < r.frames; ++f) {
    const FrameRequest q = requestOf(r, eyeCount, uint32_t(f), FrameMode::PathTraced);
    for (int e = 0; e < eyeCount; ++e)
      m.primaryMs += timePrimaryRays(ctx.scene, ctx.embree, q.eyes[e]).milliseconds;
    StereoFrame frame = pipeline.render(q);
    for (int e = 0; e < eyeCount; ++e) accumulate(m.eyes[e], frame.images[e], f);
    m.wallMs += frame.times.traceMs;
    m.rays += frame.times.rays;
    m.stages.add(frame.times);
    pipeline.recycle(std::move(frame));
  }
  m.cpuMs = m.wallMs;
  return m;
}

void score(ModeResult& m, const Reference& ref, float exposure) {
  std::vector<glm::vec3> all, refAll;
  for (size_t e = 0; e < m.eyes.size(); ++e) {
    all.insert(all.end(), m.eyes[e].color.begin(), m.eyes[e].color.end());
    refAll.insert(refAll.end(), ref.eyes[e].begin(), ref.eyes[e].end());
  }
  m.relMse = relMse(all, refAll);
  m.psnr = psnrDisplay(all, refAll, exposure);
}

HeatPanel panel(const char* label, const ModeResult& m, const Reference& ref, int w, int h) {
  HeatPanel p{label, w * int(m.eyes.size()), h, {}};
  p.values.assign(size_t(p.width) * h, 0.0f);
  for (size_t e = 0; e < m.eyes.size(); ++e) {
    const std::vector<float> map = relMseMap(m.eyes[e].color, ref.eyes[e]);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        p.values[size_t(y) * p.width + e * w + x] = map[size_t(h - 1 - y) * w + x];
  }
  return p;
}

std::string summaryText(const AbRequest& a, const ModeResult& hy, const ModeResult& pt,
                        const Reference& ref, const PipelineTimes& pipe) {
  const RenderRequest& r = a.render;
  const double equalError = pt.wallMs * (pt.relMse / std::max(hy.relMse, 1e-30)) / hy.wallMs;
  char buf[8192];
  std::snprintf(
      buf, sizeof buf,
      "photovr ab: %s, %dx%d x %zu eyes, %d spp x %d frames, %d bounces; reference %d spp\n"
      "                 relMSE      PSNR(dB)  wall ms   tracer CPU ms  Mrays/s\n"
      "hybrid        %10.3e  %8.2f  %8.1f  %12.1f  %7.2f\n"
      "pt            %10.3e  %8.2f  %8.1f  %12.1f  %7.2f\n"
      "hybrid stages (ms): G-buffer %.1f, read-back %.1f, hit rebuild %.1f, trace %.1f;"
      " %llu shared-edge hits clamped\n"
      "primary hits, pt (traversal + surface): %.1f ms; hybrid (record -> exact hit + surface):"
      " %.1f ms (%s)\n"
      "speed-up of hybrid over pt at equal spp:\n"
      "  wall-clock on this machine (Mesa rasterizes the G-buffer on the same CPU cores): %.2fx\n"
      "  tracer CPU time, GL excluded (as with a GPU running GL beside the CPU):        %.2fx\n"
      "speed-up at equal error (wall-clock, from relMSE ~ 1/time): %.2fx\n"
      "4-frame hybrid sequence: sequential %.0f ms; pipelined (PBO read-back, G-buffer of\n"
      "  frame N+1 queued before tracing N) %.0f ms, of which %.0f ms waiting for GL\n"
      "tracer per eye (ms, first / second traced; left / right with stereo reuse off), stereo\n"
      "  reuse %s: hybrid %.1f / %.1f, pt %.1f / %.1f\n",
      r.sceneSpec.c_str(), r.width, r.height, hy.eyes.size(), r.spp, r.frames, r.bounces,
      ref.samplesPerPixel, hy.relMse, hy.psnr, hy.wallMs, hy.cpuMs, hy.rays / hy.wallMs * 1e-3,
      pt.relMse, pt.psnr, pt.wallMs, pt.cpuMs, pt.rays / pt.wallMs * 1e-3, hy.stages.gbufferMs,
      hy.stages.readbackMs, hy.stages.rebuildMs, hy.stages.traceMs,
      (unsigned long long)hy.stages.outsideHits, pt.primaryMs, hy.stages.rebuildMs,
      hy.stages.rebuildMs < pt.primaryMs ? "rebuild is cheaper" : "rebuild is NOT cheaper",
      pt.wallMs / hy.wallMs, pt.cpuMs / hy.cpuMs, equalError, pipe.sequentialMs, pipe.pipelinedMs,
      pipe.waitMs, r.stereoReuse ? "on" : "off", hy.stages.turnTraceMs[0], hy.stages.turnTraceMs[1],
      pt.stages.turnTraceMs[0], pt.stages.turnTraceMs[1]);
  return buf;
}

}  // namespace

int runAb(const Args& args) {
  if (wantsHelp(args)) {
    std::cout << kAbHelp << kHeadHelp << kEyesHelp;
    return 0;
  }
  const AbRequest a = parseAb(args, false);
  const RenderRequest& r = a.render;
  const int eyeCount = r.view.stereo ? 2 : 1;
  const Reference ref =
      loadOrRenderReference({&r.scene, r.view, r.width, r.height, r.bounces}, a.referenceSpp);
  auto context = gl::createRenderContext(r.backend);
  PipelineConfig config;
  config.layout = hmd::HeadsetDescription::dk2().layout(r.width, r.height);
  FramePipeline pipeline(r.scene, config, context.get());
  ModeResult hy = runHybrid(pipeline, r, eyeCount);
  ModeResult pt = runPathTraced(pipeline, r, eyeCount);
  const PipelineTimes pipe = measurePipeline(pipeline, r, eyeCount);
  score(hy, ref, r.exposure);
  score(pt, ref, r.exposure);
  std::vector<const EyeImage*> hp, pp;
  std::vector<EyeImage> refEyes(eyeCount);
  for (int e = 0; e < eyeCount; ++e) {
    hp.push_back(&hy.eyes[e]);
    pp.push_back(&pt.eyes[e]);
    refEyes[e] = hy.eyes[e];
    refEyes[e].color = ref.eyes[e];
  }
  std::vector<const EyeImage*> rp;
  for (const EyeImage& e : refEyes) rp.push_back(&e);
  writeImage(r.outDir + "/hybrid.png", sideBySide(hp, r.exposure));
  writeImage(r.outDir + "/pt.png", sideBySide(pp, r.exposure));
  writeImage(r.outDir + "/reference.png", sideBySide(rp, r.exposure));
  writeImage(r.outDir + "/heatmap.png",
             heatMapImage({panel("HYBRID RELMSE", hy, ref, r.width, r.height),
                           panel("PT RELMSE", pt, ref, r.width, r.height)},
                          1e-4f, 10.0f));
  const std::string summary = summaryText(a, hy, pt, ref, pipe);
  std::ofstream(r.outDir + "/summary.txt") << summary;
  std::cout << summary << "wrote " << r.outDir
            << "/{hybrid,pt,reference,heatmap}.png and summary.txt\n";
  return 0;
}

int runReference(const Args& args) {
  if (wantsHelp(args)) {
    std::cout << kReferenceHelp << kHeadHelp << kEyesHelp;
    return 0;
  }
  const AbRequest a = parseAb(args, true);
  const RenderRequest& r = a.render;
  const ReferenceSpec spec{&r.scene, r.view, r.width, r.height, r.bounces};
  if (a.shard) {
    const ShardResult s = renderReferenceShard(spec, r.spp, *a.shard);
    if (!s.complete) {
      std::printf("reference: shard %d/%d done in %s; the set is not complete yet\n",
                  a.shard->index, a.shard->count, s.reference.directory.c_str());
      return 0;
    }
    std::printf("reference: %d spp in %s (merged; estimated relMSE %.2e)\n",
                s.reference.samplesPerPixel, s.reference.directory.c_str(),
                s.reference.estimatedRelMse);
    return 0;
  }
  const Reference ref = loadOrRenderReference(spec, r.spp);
  std::printf("reference: %d spp in %s\n", ref.samplesPerPixel, ref.directory.c_str());
  return 0;
}

}  // namespace photovr::app
