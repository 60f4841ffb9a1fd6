#include "hybrid/frame_pipeline.h"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "core/parallel_ranges.h"
#include "core/stopwatch.h"
#include "hybrid/denoise_input.h"

namespace photovr {
namespace {

// 'c' with alpha 1, into 'out' (storage reused; in parallel, as fillDenoiseInput).
const std::vector<glm::vec4>& withAlpha(const std::vector<glm::vec3>& c,
                                        std::vector<glm::vec4>& out) {
  out.resize(c.size());
  parallelRanges(c.size(), [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) out[i] = glm::vec4(c[i], 1.0f);
  });
  return out;
}

bool needsGBuffer(const FrameSettings& s) {
  return s.mode == FrameMode::Hybrid || s.denoise != gl::DenoiseMode::Off;
}

}  // namespace

TraceSettings traceSettingsOf(const FrameSettings& f, const WorkSkips& skips) {
  TraceSettings s;
  s.samplesPerPixel = f.spp;
  s.maxBounces = f.bounces;
  s.seed = f.seed;
  s.sampler = f.sampler;
  s.stereoReuse = f.stereoReuse;
  s.caustics = f.caustics;
  s.skips = skips;
  return s;
}

const char* frameModeName(FrameMode mode) {
  return mode == FrameMode::Hybrid ? "hybrid" : "pt";
}

FramePipeline::FramePipeline(const Scene& scene, const PipelineConfig& config, gl::Context* context)
    : config_(config) {
  TraceSettings base;
  base.skips = config.skips;
  if (context) {
    hybrid_ =
        std::make_unique<HybridRenderer>(scene, config.layout.width, config.layout.height, base);
  } else {
    embree_ = std::make_unique<EmbreeScene>(scene, config.skips);
    lights_ = std::make_unique<LightSet>(scene, config.skips);
    cpuContext_ = std::make_unique<TraceContext>(TraceContext{scene, *embree_, *lights_, base});
  }
}

FramePipeline::~FramePipeline() {
  if (!worker_.joinable()) return;
  {
    std::lock_guard lock(mutex_);
    quit_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

const TraceContext& FramePipeline::traceContext() const {
  return hybrid_ ? hybrid_->traceContext() : *cpuContext_;
}

EmbreeScene& FramePipeline::embree() {
  return hybrid_ ? hybrid_->embree() : *embree_;
}

const StereoSampleMaps& FramePipeline::sampleMaps(SampleMapKind kind, int spp) {
  const auto key = std::pair(kind, spp);
  auto it = maps_.find(key);
  if (it == maps_.end())
    it = maps_.emplace(key, lensSampleMaps(kind, config_.layout, spp, config_.lens)).first;
  return it->second;
}

void FramePipeline::requireGl(const char* what) const {
  if (!hybrid_)
    throw std::logic_error(std::string("FramePipeline: ") + what + " needs a GL context");
}

void FramePipeline::animate(Scene& scene) {
  if (&scene != &traceContext().scene)
    throw std::logic_error("FramePipeline::animate: not the scene the pipeline was built on");
  animated_ = &scene;
}

void FramePipeline::pose(StereoFrame& frame) {
  const double t = frame.request.sceneTime;
  if (!animated_ || std::isnan(t) || t == posedTime_) return;
  const auto t0 = Clock::now();
  const double previous = std::isnan(posedTime_) ? t - kAnimationFrameSeconds : posedTime_;
  const SceneMotion motion = poseScene(*animated_, t, previous);
  if (hybrid_)
    hybrid_->sceneMoved(motion);
  else
    moveTracerScene(*embree_, *lights_, motion);
  posedTime_ = t;
  frame.times.animateMs = msSince(t0);
}

void FramePipeline::begin(Job& job) {
  pose(job.frame);
  const FrameRequest& r = job.frame.request;
  if (!needsGBuffer(r.settings)) return;
  requireGl(r.settings.mode == FrameMode::Hybrid ? "a hybrid frame" : "the denoiser");
  job.maps = &sampleMaps(r.settings.sampleMap, r.settings.spp);
  const auto t0 = Clock::now();
  hybrid_->drawGBuffer(r.eyes);
  if (r.settings.mode == FrameMode::PathTraced) {  // the denoiser's guides, never read back
    job.frame.times.gbufferMs = msSince(t0);
    return;
  }
  const double drawMs = msSince(t0);
  hybrid_->readGBuffer(r.eyeCount, job.gbuffers, job.frame.times);
  job.frame.times.gbufferMs += drawMs;  // draw calls, then the wait for GL to finish them
}

void FramePipeline::trace(Job& job) {
  StereoFrame& f = job.frame;
  const FrameRequest& r = f.request;
  {
    std::lock_guard lock(mutex_);
    std::array<EyeImage, 2> recycled = std::exchange(recycled_, {});
    if (r.settings.mode == FrameMode::Hybrid)
      hybrid_->recycle(std::move(recycled));
    else
      for (int e = 0; e < 2; ++e)
        if (!recycled[e].color.empty()) ptBuffers_[e] = std::move(recycled[e]);
  }
  const TraceSettings settings = traceSettingsOf(r.settings, config_.skips);
  if (r.settings.mode == FrameMode::Hybrid) {
    f.images =
        hybrid_->trace(job.gbuffers, r.eyes, r.eyeCount, r.index, settings, f.times, *job.maps);
    return;
  }
  TraceContext ctx = traceContext();
  ctx.settings = settings;
  StereoTurns turns = stereoTurnsOf(settings.stereoReuse, r.eyeCount, r.index, ptStereo_, r.eyes[0],
                                    uint32_t(settings.samplesPerPixel));
  for (StereoRole& role : turns.roles) role.caustics = &ptCaustics_;
  for (int k = 0; k < r.eyeCount; ++k) {
    const int e = turns.order[k];
    const auto t0 = Clock::now();
    f.images[e] = renderPathTraced(ctx, r.eyes[e], uint32_t(e), r.index, std::move(ptBuffers_[e]),
                                   turns.roles[e]);
    f.times.turnTraceMs[k] = msSince(t0);
    f.times.traceMs += f.times.turnTraceMs[k];
    f.times.addTurn(k, f.images[e]);
  }
}

gl::Denoiser& FramePipeline::denoiserForUse() {
  if (!denoiser_) {
    requireGl("the denoiser");
    denoiser_ = std::make_unique<gl::Denoiser>(config_.layout.width, config_.layout.height,
                                               config_.denoiser);
    denoiser_->setTiming(config_.timeDenoiserPasses);
  }
  return *denoiser_;
}

void FramePipeline::prepare(const FrameSettings& s) {
  if (s.denoise != gl::DenoiseMode::Off) denoiserForUse();
  if (s.mode == FrameMode::Hybrid) sampleMaps(s.sampleMap, s.spp);
}

// The denoiser's history carries over only between denoised frames of one mode: a frame of
// the other renderer, or one shown undenoised, starts a new one.
void FramePipeline::finish(StereoFrame& f) {
  const FrameRequest& r = f.request;
  const auto t0 = Clock::now();
  if (r.settings.denoise != gl::DenoiseMode::Off) {
    denoiserForUse();
    const bool reset = !historyValid_ || historyMode_ != r.settings.mode;
    for (int e = 0; e < r.eyeCount; ++e) fillDenoiseInput(f.images[e], denoiseInputs_[e]);
    denoiser_->run(hybrid_->gbuffer(), {denoiseInputs_[0].eye, denoiseInputs_[r.eyeCount - 1].eye},
                   r.eyeCount, r.settings.denoise, reset);
    historyValid_ = true;
    historyMode_ = r.settings.mode;
    f.denoised = true;
    f.display = {denoiser_->linearTexture(), denoiser_->depthTexture()};
    for (const gl::PassTiming& p : denoiser_->timings()) f.times.denoisePassMs += p.ms;
  } else {
    historyValid_ = false;
    if (config_.forDisplay) {
      requireGl("a display upload");
      if (!upload_)
        upload_ = std::make_unique<gl::EyeArrays>(config_.layout.width, config_.layout.height);
      for (int e = 0; e < r.eyeCount; ++e)
        upload_->upload(e, withAlpha(f.images[e].color, uploadColor_), f.images[e].depth);
      f.display = {upload_->color(), upload_->depth()};
    }
  }
  f.times.denoiseMs = msSince(t0);
}

StereoFrame FramePipeline::render(const FrameRequest& request) {
  Job job;
  job.frame.request = request;
  std::swap(job.gbuffers, gbuffers_);
  begin(job);
  trace(job);
  std::swap(job.gbuffers, gbuffers_);
  finish(job.frame);
  return std::move(job.frame);
}

void FramePipeline::renderSequence(const RequestFn& requests, int frames, Scheduling scheduling,
                                   const FrameFn& onFrame, FrameTimes* totals) {
  FrameTimes sum;
  if (scheduling == Scheduling::Sequential) {
    for (int f = 0; f < frames; ++f) {
      StereoFrame frame = render(requests(uint32_t(f)));
      sum.add(frame.times);
      onFrame(frame);
      recycle(std::move(frame));
    }
  } else {
    const FrameRequest first = requests(0);
    if (first.settings.denoise != gl::DenoiseMode::Off)
      throw std::logic_error(
          "FramePipeline: pipelined frames cannot be denoised (the guides "
          "would be the next frame's)");
    if (animated_)
      throw std::logic_error("FramePipeline: pipelined scheduling cannot pose an animated scene");
    if (first.settings.mode != FrameMode::Hybrid ||
        first.settings.sampleMap != SampleMapKind::Uniform)
      throw std::logic_error("FramePipeline: pipelined scheduling is for uniform hybrid frames");
    requireGl("a hybrid frame");
    hybrid_->setSettings(traceSettingsOf(first.settings, config_.skips));
    hybrid_->renderSequence([&](uint32_t f) { return f == 0 ? first.eyes : requests(f).eyes; },
                            frames, first.eyeCount, true,
                            [&](uint32_t f, std::array<EyeImage, 2>& images) {
                              StereoFrame frame;
                              frame.request = f == 0 ? first : requests(f);
                              frame.images = std::move(images);
                              onFrame(frame);
                              images = std::move(frame.images);
                            },
                            &sum);
  }
  if (totals) *totals = sum;
}

void FramePipeline::recycle(StereoFrame&& frame) {
  std::lock_guard lock(mutex_);
  for (int e = 0; e < 2; ++e)
    if (!frame.images[e].color.empty()) recycled_[e] = std::move(frame.images[e]);
}

bool FramePipeline::busy() const {
  std::lock_guard lock(mutex_);
  return working_ || done_.has_value() || failure_;
}

void FramePipeline::start(const FrameRequest& request) {
  if (!worker_.joinable()) worker_ = std::thread([this] { workerLoop(); });
  Job job;
  job.frame.request = request;
  {
    std::lock_guard lock(mutex_);
    std::swap(job.gbuffers, spareGBuffers_);
  }
  begin(job);
  {
    std::lock_guard lock(mutex_);
    job_ = std::move(job);
    working_ = true;
  }
  wake_.notify_all();
}

std::optional<StereoFrame> FramePipeline::take() {
  std::optional<StereoFrame> out;
  {
    std::lock_guard lock(mutex_);
    if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
    out = std::move(done_);
    done_.reset();
  }
  if (out) finish(*out);
  return out;
}

void FramePipeline::workerLoop() {
  enableFlushToZero();  // in every tracing thread (denormals, trace/sampling.h)
  for (;;) {
    std::unique_lock lock(mutex_);
    wake_.wait(lock, [&] { return quit_ || job_.has_value(); });
    if (quit_) return;
    Job job = std::move(*job_);
    job_.reset();
    lock.unlock();
    std::exception_ptr failure;
    try {
      trace(job);
    } catch (...) {  // handed to the GL thread: it reports, this thread keeps serving
      failure = std::current_exception();
    }
    lock.lock();
    spareGBuffers_ = std::move(job.gbuffers);
    if (!failure) done_ = std::move(job.frame);
    failure_ = failure;
    working_ = false;
  }
}

}  // namespace photovr
