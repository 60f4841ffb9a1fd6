#include "hybrid/hybrid_renderer.h"

#include <chrono>

#include "core/stopwatch.h"
#include "gl/gbuffer_readback.h"

namespace photovr {

void FrameTimes::add(const FrameTimes& t) {
  gbufferMs += t.gbufferMs, readbackMs += t.readbackMs;
  rebuildMs += t.rebuildMs, traceMs += t.traceMs, refitMs += t.refitMs;
  for (int e = 0; e < 2; ++e) {
    turnTraceMs[e] += t.turnTraceMs[e];
    turnPaths[e] += t.turnPaths[e];
    turnReusedPaths[e] += t.turnReusedPaths[e];
    turnOwnBounces[e] += t.turnOwnBounces[e];
    turnCausticMs[e] += t.turnCausticMs[e];
  }
  causticSplats += t.causticSplats;
  animateMs += t.animateMs;
  denoiseMs += t.denoiseMs, denoisePassMs += t.denoisePassMs;
  rays += t.rays, outsideHits += t.outsideHits, rejectedSamples += t.rejectedSamples;
}

void FrameTimes::addTurn(int turn, const EyeImage& image) {
  rays += image.rays;
  rejectedSamples += image.rejectedSamples;
  turnPaths[turn] += image.paths;
  turnReusedPaths[turn] += image.reusedPaths;
  turnOwnBounces[turn] += image.reusedOwnBounces;
  turnCausticMs[turn] += image.causticMs;
  causticSplats += image.causticSplats;
}

HybridRenderer::HybridRenderer(const Scene& scene, int w, int h, const TraceSettings& settings)
    : scene_(scene),
      gpu_(scene),
      pass_(w, h),
      embree_(scene, settings.skips),
      lights_(scene, settings.skips),
      ctx_{scene, embree_, lights_, settings} {}

void moveTracerScene(EmbreeScene& embree, LightSet& lights, const SceneMotion& motion) {
  embree.updateMeshVertices(motion.deformedMeshes);
  embree.updateInstanceTransforms();
  if (motion.lightsMoved) lights.update();
}

void HybridRenderer::sceneMoved(const SceneMotion& motion) {
  gpu_.updateInstances(scene_);
  gpu_.updateMeshVertices(scene_, motion.deformedMeshes);
  moveTracerScene(embree_, lights_, motion);
}

void HybridRenderer::drawGBuffer(const std::array<EyeCamera, 2>& eyes) {
  std::array<glm::mat4, 2> vp;
  for (int e = 0; e < 2; ++e) vp[e] = eyes[e].unjitteredProjection() * eyes[e].view();
  pass_.render(gpu_, eyes, hasPrevious_ ? previousViewProjection_ : vp);
  previousViewProjection_ = vp;
  hasPrevious_ = true;
}

void HybridRenderer::readGBuffer(int eyeCount, std::array<gl::GBufferImage, 2>& into,
                                 FrameTimes& t) {
  const auto t0 = Clock::now();
  pass_.finish();
  const auto t1 = Clock::now();
  for (int e = 0; e < eyeCount; ++e) pass_.read(e, into[e], gl::GBufferRead::Visibility);
  t.gbufferMs = msBetween(t0, t1);
  t.readbackMs = msSince(t1);
}

std::array<EyeImage, 2> HybridRenderer::trace(const std::array<gl::GBufferImage, 2>& g,
                                              const std::array<EyeCamera, 2>& eyes, int eyeCount,
                                              uint32_t frame, const TraceSettings& settings,
                                              FrameTimes& t, const StereoSampleMaps& samples) {
  std::array<EyeImage, 2> out;
  TraceContext ctx = ctx_;
  ctx.settings = settings;
  ctx.settings.skips = ctx_.settings.skips;  // the scene was built for these
  if (!ctx.settings.skips.refit) {           // a static scene never needs this (work_skips.h)
    const auto t0 = Clock::now();
    embree_.updateInstanceTransforms();
    t.refitMs += msBetween(t0, Clock::now());
  }
  StereoTurns turns = stereoTurnsOf(settings.stereoReuse, eyeCount, frame, stereo_, eyes[0],
                                    uint32_t(settings.samplesPerPixel));
  for (StereoRole& role : turns.roles) role.caustics = &caustics_;
  for (int k = 0; k < eyeCount; ++k) {
    const int e = turns.order[k];
    HybridEyeStats s;
    out[e] = traceFromGBuffer(ctx, g[e], eyes[e], uint32_t(e), frame, samples[e], &s,
                              &eyeBuffers_[e], turns.roles[e]);
    t.rebuildMs += s.rebuildMs;
    t.traceMs += s.traceMs;
    t.turnTraceMs[k] += s.rebuildMs + s.traceMs;
    t.outsideHits += s.outsideHits;
    t.addTurn(k, out[e]);
  }
  return out;
}

std::array<EyeImage, 2> HybridRenderer::render(const std::array<EyeCamera, 2>& eyes, int eyeCount,
                                               uint32_t frame, FrameTimes* times,
                                               const StereoSampleMaps& samples) {
  const auto t0 = Clock::now();
  drawGBuffer(eyes);
  const double drawMs = msSince(t0);
  FrameTimes t;
  readGBuffer(eyeCount, gbuffers_, t);
  t.gbufferMs += drawMs;  // draw calls, then the wait for GL to finish them
  auto out = trace(gbuffers_, eyes, eyeCount, frame, ctx_.settings, t, samples);
  if (times) *times = t;
  return out;
}

void HybridRenderer::recycle(std::array<EyeImage, 2>&& images) {
  for (int e = 0; e < 2; ++e)
    if (!images[e].color.empty()) eyeBuffers_[e].image = std::move(images[e]);
}

void HybridRenderer::renderSequence(const CameraFn& cameras, int frames, int eyeCount,
                                    bool pipelined, const FrameFn& onFrame, FrameTimes* totals) {
  FrameTimes sum;
  if (!pipelined) {
    for (int f = 0; f < frames; ++f) {
      FrameTimes t;
      auto images = render(cameras(uint32_t(f)), eyeCount, uint32_t(f), &t);
      onFrame(uint32_t(f), images);
      recycle(std::move(images));
      sum.add(t);
    }
  } else {
    // Stage times overlap here; gbufferMs counts only the time the CPU waited for GL.
    gl::GBufferReadback readback[2] = {gl::GBufferReadback(pass_, gl::GBufferRead::Visibility),
                                       gl::GBufferReadback(pass_, gl::GBufferRead::Visibility)};
    std::array<EyeCamera, 2> current = cameras(0);
    drawGBuffer(current);
    readback[0].start(eyeCount);
    for (int f = 0; f < frames; ++f) {
      std::array<EyeCamera, 2> next;
      if (f + 1 < frames) {
        next = cameras(uint32_t(f + 1));
        drawGBuffer(next);
        readback[(f + 1) % 2].start(eyeCount);
      }
      const auto t0 = Clock::now();
      readback[f % 2].finish(gbuffers_);
      sum.gbufferMs += msBetween(t0, Clock::now());
      auto images = trace(gbuffers_, current, eyeCount, uint32_t(f), ctx_.settings, sum, {});
      onFrame(uint32_t(f), images);
      recycle(std::move(images));
      current = next;
    }
  }
  if (totals) *totals = sum;
}

}  // namespace photovr
