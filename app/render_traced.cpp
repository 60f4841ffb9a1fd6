// photovr render --mode hybrid|pt: frames accumulated with sub-pixel jitter, both eyes.
#include <chrono>
#include <cstdio>
#include <functional>
#include <utility>

#include "app/gl_context.h"
#include "app/render_request.h"
#include "app/sample_maps.h"
#include "app/trace_output.h"
#include "gl/denoiser.h"
#include "hybrid/denoise_input.h"
#include "hybrid/hybrid_renderer.h"
#include "trace/convergence.h"
#include "trace/embree_scene.h"
#include "trace/lights.h"

namespace photovr::app {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

gl::DenoiseParams paramsOf(const RenderRequest& r) {
  gl::DenoiseParams params;
  params.exposure = r.exposure;
  return params;
}

using FrameRenderer =
    std::function<std::array<EyeImage, 2>(const std::array<EyeCamera, 2>&, uint32_t)>;
// Takes a frame's images back once they are accumulated (HybridRenderer::recycle).
using FrameRecycler = std::function<void(std::array<EyeImage, 2>&&)>;

// Renders r.frames frames (jitter from the frame index) and returns the per-eye means; with
// r.converge > 0 it stops as soon as the estimated relMSE of the mean drops below it (the
// view is static, so later frames would only refine a converged image).
std::vector<EyeImage> accumulateFrames(const RenderRequest& r, const FrameRenderer& renderFrame,
                                       int& framesDone, const FrameRecycler& recycle = {}) {
  const int eyeCount = r.view.stereo ? 2 : 1;
  std::vector<EyeImage> sums(eyeCount);
  ConvergenceMonitor monitor;
  const auto t0 = Clock::now();
  uint64_t rays = 0;
  for (framesDone = 0; framesDone < r.frames;) {
    const int f = framesDone;
    auto frame =
        renderFrame(eyeCameras(r.view, r.width, r.height, uint32_t(f), r.sampler), uint32_t(f));
    for (int e = 0; e < eyeCount; ++e) {
      rays += frame[e].rays;
      accumulate(sums[e], frame[e], f);
      if (r.converge > 0.0) monitor.add(e, frame[e].color, r.width);
    }
    if (recycle) recycle(std::move(frame));
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
  std::vector<std::string> written;
  std::vector<const EyeImage*> ptrs;
  uint64_t rays = 0, rejected = 0;
  for (size_t e = 0; e < eyes.size(); ++e) {
    for (const std::string& p : writeEyeImages(eyes[e], r.outDir + "/" + eyeFolder(r.view, int(e))))
      written.push_back(p);
    ptrs.push_back(&eyes[e]);
    rays += eyes[e].rays;
    rejected += eyes[e].rejectedSamples;
  }
  writeImage(r.outDir + "/color.png", sideBySide(ptrs, r.exposure));
  written.push_back(r.outDir + "/color.png");
  std::printf("scene %s: %zu triangles, %s\n", r.sceneSpec.c_str(),
              r.scene.instancedTriangleCount(), r.view.description.c_str());
  std::printf(
      "%s %dx%d x %zu eyes, %d spp x %d frames, %d bounces: %.2f s, %.2f Mrays/s, "
      "%llu samples rejected (NaN/Inf)\n",
      r.mode.c_str(), r.width, r.height, eyes.size(), r.spp, frames, r.bounces, seconds,
      rays / seconds * 1e-6, (unsigned long long)rejected);
  std::printf("stages per frame: %s\nwrote:\n", stages.c_str());
  for (const std::string& p : written) std::printf("  %s\n", p.c_str());
}

// The denoiser's last frame: denoised.png (both eyes) and per eye denoised.exr (linear).
void writeDenoised(const RenderRequest& r, const gl::Denoiser& denoiser, int eyeCount) {
  Image8 display(r.width * eyeCount, r.height, 3);
  for (int e = 0; e < eyeCount; ++e) {
    const std::vector<glm::u8vec4> d = denoiser.readDisplay(e);
    for (int y = 0; y < r.height; ++y)
      for (int x = 0; x < r.width; ++x) {
        const glm::u8vec4 c = d[size_t(r.height - 1 - y) * r.width + x];
        uint8_t* p = display.at(e * r.width + x, y);
        p[0] = c.r, p[1] = c.g, p[2] = c.b;
      }
    const std::string path = r.outDir + "/" + eyeFolder(r.view, e) + "/denoised.exr";
    writeImage(path, toImage(denoiser.readLinear(e), r.width, r.height));
    std::printf("  %s\n", path.c_str());
  }
  writeImage(r.outDir + "/denoised.png", display);
  std::printf("  %s/denoised.png\n", r.outDir.c_str());
}

// A G-buffer drawn only to guide the denoiser of a path-traced frame.
struct GuideBuffers {
  gl::SceneGpu gpu;
  gl::GBufferPass pass;
  gl::Denoiser denoiser;
  std::array<glm::mat4, 2> previous{};

  GuideBuffers(const RenderRequest& r, const gl::Context& ctx)
      : gpu(r.scene),
        pass(r.width, r.height, ctx.hasExtension("GL_ARB_shader_viewport_layer_array"),
             gl::EyeRouting::Layered),
        denoiser(r.width, r.height, paramsOf(r)) {}

  void denoise(const std::array<EyeCamera, 2>& eyes, const std::array<EyeImage, 2>& images,
               int eyeCount, gl::DenoiseMode mode, uint32_t frame) {
    std::array<glm::mat4, 2> vp;
    for (int e = 0; e < 2; ++e) vp[e] = eyes[e].unjitteredProjection() * eyes[e].view();
    pass.render(gpu, eyes, frame == 0 ? vp : previous);
    previous = vp;
    const DenoiseInput left = makeDenoiseInput(images[0]);
    const DenoiseInput right = makeDenoiseInput(images[eyeCount - 1]);
    denoiser.run(pass, {left.eye, right.eye}, eyeCount, mode, frame == 0);
  }
};

}  // namespace

TraceSettings traceSettingsOf(const RenderRequest& r) {
  TraceSettings s;
  s.samplesPerPixel = r.spp;
  s.maxBounces = r.bounces;
  s.seed = r.seed;
  s.sampler = r.sampler;
  s.skips = r.skips;
  return s;
}

int renderPathTracedMode(const RenderRequest& r) {
  const auto t0 = Clock::now();
  const EmbreeScene embree(r.scene, r.skips);
  const LightSet lights(r.scene, r.skips);
  const TraceContext ctx{r.scene, embree, lights, traceSettingsOf(r)};
  const double buildMs = 1e3 * secondsSince(t0);
  const int eyeCount = r.view.stereo ? 2 : 1;
  // Denoising pt uses the same denoiser, guided by a G-buffer drawn only for its guides
  // (normals, depth, motion, ids); the traced image never depends on it.
  const gl::DenoiseMode denoiseMode = gl::parseDenoiseMode(r.denoise);
  std::unique_ptr<gl::Context> context;
  std::unique_ptr<GuideBuffers> guides;
  if (denoiseMode != gl::DenoiseMode::Off) {
    context = createRenderContext(r.backend);
    guides = std::make_unique<GuideBuffers>(r, *context);
  }
  double traceMs = 0.0, denoiseMs = 0.0;
  std::array<EyeImage, 2> spare;  // each frame's images once accumulated, traced into next
  const auto t1 = Clock::now();
  int frames = 0;
  const auto sums = accumulateFrames(
      r,
      [&](const std::array<EyeCamera, 2>& eyes, uint32_t f) {
        const auto ts = Clock::now();
        std::array<EyeImage, 2> out;
        for (int e = 0; e < eyeCount; ++e)
          out[e] = renderPathTraced(ctx, eyes[e], uint32_t(e), f, std::move(spare[e]));
        traceMs += 1e3 * secondsSince(ts);
        if (guides) {
          const auto td = Clock::now();
          guides->denoise(eyes, out, eyeCount, denoiseMode, f);
          denoiseMs += 1e3 * secondsSince(td);
        }
        return out;
      },
      frames, [&](std::array<EyeImage, 2>&& images) { spare = std::move(images); });
  char stages[192];
  std::snprintf(stages, sizeof stages,
                "BVH build %.0f ms (once), trace %.1f ms, denoise (%s) %.1f ms", buildMs,
                traceMs / frames, r.denoise.c_str(), denoiseMs / frames);
  writeAndReport(r, sums, frames, secondsSince(t1), stages);
  if (guides) writeDenoised(r, guides->denoiser, eyeCount);
  return 0;
}

int renderHybridMode(const RenderRequest& r) {
  auto context = createRenderContext(r.backend);
  HybridRenderer renderer(r.scene, r.width, r.height,
                          context->hasExtension("GL_ARB_shader_viewport_layer_array"),
                          traceSettingsOf(r));
  const int eyeCount = r.view.stereo ? 2 : 1;
  HybridFrameTimes total;
  const gl::DenoiseMode denoiseMode = gl::parseDenoiseMode(r.denoise);
  std::unique_ptr<gl::Denoiser> denoiser;
  if (denoiseMode != gl::DenoiseMode::Off) {
    denoiser = std::make_unique<gl::Denoiser>(r.width, r.height, paramsOf(r));
  }
  double denoiseMs = 0.0;
  const auto maps = lensSampleMaps(r.sampling, StereoLayout::dk2(r.width, r.height), r.spp);
  const std::array<const std::vector<uint16_t>*, 2> mapPtrs = {
      maps[0].empty() ? nullptr : &maps[0], maps[1].empty() ? nullptr : &maps[1]};
  std::printf("sampling: %s (%s)\n", r.sampling.c_str(), describeSampleMaps(maps).c_str());
  const auto t1 = Clock::now();
  int frames = 0;
  const auto sums = accumulateFrames(
      r,
      [&](const std::array<EyeCamera, 2>& eyes, uint32_t f) {
        HybridFrameTimes t;
        auto out = renderer.render(eyes, eyeCount, f, &t, mapPtrs);
        total.gbufferMs += t.gbufferMs, total.readbackMs += t.readbackMs;
        total.rebuildMs += t.rebuildMs, total.traceMs += t.traceMs, total.refitMs += t.refitMs;
        total.outsideHits += t.outsideHits;
        if (denoiser) {
          const auto t0 = Clock::now();
          const DenoiseInput left = makeDenoiseInput(out[0]);
          const DenoiseInput right = makeDenoiseInput(out[eyeCount - 1]);
          denoiser->run(renderer.gbuffer(), {left.eye, right.eye}, eyeCount, denoiseMode, f == 0);
          denoiseMs += 1e3 * secondsSince(t0);
        }
        return out;
      },
      frames, [&](std::array<EyeImage, 2>&& images) { renderer.recycle(std::move(images)); });
  char stages[320];
  const double n = frames;
  std::snprintf(stages, sizeof stages,
                "G-buffer %.1f ms, read-back %.1f ms, hit rebuild %.1f ms, trace %.1f ms, "
                "denoise (%s) %.1f ms (%llu shared-edge hits clamped)",
                total.gbufferMs / n, total.readbackMs / n, total.rebuildMs / n, total.traceMs / n,
                r.denoise.c_str(), denoiseMs / n, (unsigned long long)total.outsideHits);
  writeAndReport(r, sums, frames, secondsSince(t1), stages);
  if (denoiser) writeDenoised(r, *denoiser, eyeCount);
  return 0;
}

}  // namespace photovr::app
