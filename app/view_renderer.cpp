#include "app/view_renderer.h"

#include <algorithm>
#include <chrono>
#include <utility>

#include "app/sample_maps.h"
#include "core/stopwatch.h"
#include "hybrid/hybrid_tracer.h"

namespace photovr::app {
namespace {

// Lens-matched maps are built for this spp and scaled per frame (the spp slider moves).
constexpr int kLensMapSpp = 64;

}  // namespace

ViewRenderer::ViewRenderer(const Scene& scene, const StereoLayout& eyes, bool hasLayerExtension)
    : scene_(scene),
      gpu_(scene),
      pass_(eyes.width, eyes.height, hasLayerExtension, gl::EyeRouting::Layered),
      embree_(scene),
      lights_(scene),
      lensMaps_(lensSampleMaps("lens-matched", eyes, kLensMapSpp)),
      worker_([this] { workerLoop(); }) {}

ViewRenderer::~ViewRenderer() {
  {
    std::lock_guard lock(mutex_);
    quit_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

bool ViewRenderer::busy() const {
  std::lock_guard lock(mutex_);
  return working_ || done_.has_value() || failure_;
}

void ViewRenderer::start(const std::array<EyeCamera, 2>& eyes, const FrameSettings& settings) {
  const auto t0 = Clock::now();
  std::array<glm::mat4, 2> vp;
  for (int e = 0; e < 2; ++e) vp[e] = eyes[e].unjitteredProjection() * eyes[e].view();
  pass_.render(gpu_, eyes, nextIndex_ == 0 ? vp : previousVp_);
  previousVp_ = vp;
  pass_.finish();
  FinishedFrame job;
  job.index = nextIndex_++;
  job.eyes = eyes;
  job.settings = settings;
  job.gbufferMs = msSince(t0);
  std::array<gl::GBufferImage, 2> g;
  {
    std::lock_guard lock(mutex_);
    std::swap(g, spare_);
  }
  const auto t1 = Clock::now();
  for (int e = 0; e < 2; ++e) pass_.read(e, g[e]);
  job.readbackMs = msSince(t1);
  {
    std::lock_guard lock(mutex_);
    job_.emplace(std::move(job), std::move(g));
    working_ = true;
  }
  wake_.notify_all();
}

std::optional<FinishedFrame> ViewRenderer::take() {
  std::lock_guard lock(mutex_);
  if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
  std::optional<FinishedFrame> out = std::move(done_);
  done_.reset();
  return out;
}

void ViewRenderer::recycle(std::array<EyeImage, 2>&& images) {
  std::lock_guard lock(mutex_);
  spareImages_ = std::move(images);
}

FinishedFrame ViewRenderer::trace(FinishedFrame f, const std::array<gl::GBufferImage, 2>& g) {
  const auto t0 = Clock::now();
  TraceContext ctx{scene_, embree_, lights_, {}};
  ctx.settings.samplesPerPixel = f.settings.spp;
  ctx.settings.maxBounces = f.settings.bounces;
  ctx.settings.seed = 0;
  for (int e = 0; e < 2; ++e) {
    if (f.settings.pathTraced) {
      f.images[e] =
          renderPathTraced(ctx, f.eyes[e], uint32_t(e), f.index, std::move(eyeBuffers_[e].image));
      continue;
    }
    std::vector<uint16_t> map;
    if (f.settings.lensMatched) {  // rescale the kLensMapSpp map to this frame's spp
      map = lensMaps_[e];
      for (uint16_t& s : map)
        if (s) s = uint16_t(std::max(1, (s * f.settings.spp + kLensMapSpp - 1) / kLensMapSpp));
    }
    HybridEyeStats stats;
    f.images[e] =
        traceFromGBuffer(ctx, g[e], f.eyes[e], uint32_t(e), f.index,
                         f.settings.lensMatched ? &map : nullptr, &stats, &eyeBuffers_[e]);
  }
  f.traceMs = msSince(t0);
  f.totalMs = f.gbufferMs + f.readbackMs + f.traceMs;
  return f;
}

void ViewRenderer::workerLoop() {
  enableFlushToZero();  // platform.md: in every tracing thread
  for (;;) {
    std::unique_lock lock(mutex_);
    wake_.wait(lock, [&] { return quit_ || job_.has_value(); });
    if (quit_) return;
    auto job = std::move(*job_);
    job_.reset();
    for (int e = 0; e < 2; ++e)
      if (!spareImages_[e].color.empty()) eyeBuffers_[e].image = std::move(spareImages_[e]);
    spareImages_ = {};
    lock.unlock();
    std::optional<FinishedFrame> f;
    std::exception_ptr failure;
    try {
      f = trace(std::move(job.first), job.second);
    } catch (...) {  // handed to the GL thread: it reports, this thread keeps serving
      failure = std::current_exception();
    }
    lock.lock();
    spare_ = std::move(job.second);
    done_ = std::move(f);
    failure_ = failure;
    working_ = false;
  }
}

}  // namespace photovr::app
