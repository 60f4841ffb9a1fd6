#include "hybrid/hybrid_renderer.h"

#include <chrono>

namespace photovr {
namespace {

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

}  // namespace

HybridRenderer::HybridRenderer(const Scene& scene, int w, int h, bool hasLayerExtension,
                               const TraceSettings& settings)
    : scene_(scene),
      gpu_(scene),
      pass_(w, h, hasLayerExtension, gl::EyeRouting::Layered),
      embree_(scene),
      lights_(scene),
      ctx_{scene, embree_, lights_, settings} {}

std::array<EyeImage, 2> HybridRenderer::render(
    const std::array<EyeCamera, 2>& eyes, int eyeCount, uint32_t frame, HybridFrameTimes* times,
    const std::array<const std::vector<uint16_t>*, 2>& sppMaps) {
  std::array<glm::mat4, 2> vp;
  for (int e = 0; e < 2; ++e) vp[e] = eyes[e].unjitteredProjection() * eyes[e].view();
  const auto t0 = Clock::now();
  pass_.render(gpu_, eyes, hasPrevious_ ? previousViewProjection_ : vp);
  pass_.finish();
  const auto t1 = Clock::now();
  std::array<gl::GBufferImage, 2> g;
  for (int e = 0; e < eyeCount; ++e) g[e] = pass_.read(e);
  const auto t2 = Clock::now();
  previousViewProjection_ = vp;
  hasPrevious_ = true;
  std::array<EyeImage, 2> out;
  HybridFrameTimes t;
  t.gbufferMs = msBetween(t0, t1);
  t.readbackMs = msBetween(t1, t2);
  for (int e = 0; e < eyeCount; ++e) {
    HybridEyeStats s;
    out[e] = traceFromGBuffer(ctx_, g[e], eyes[e], uint32_t(e), frame, sppMaps[e], &s);
    t.rebuildMs += s.rebuildMs;
    t.traceMs += s.traceMs;
    t.outsideHits += s.outsideHits;
    t.rays += out[e].rays;
    t.rejectedSamples += out[e].rejectedSamples;
  }
  if (times) *times = t;
  return out;
}

}  // namespace photovr
