// photovr render --mode pt: both eyes path traced by Embree alone.
#include <chrono>
#include <cstdio>

#include "app/render_request.h"
#include "core/image_io.h"
#include "core/tonemap.h"
#include "trace/embree_scene.h"
#include "trace/lights.h"
#include "trace/path_tracer.h"

namespace photovr::app {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Bottom-up rows (GL's and the tracer's) to a top-down float image.
template <typename T>
ImageF toImage(const std::vector<T>& values, int w, int h, int channels) {
  ImageF img(w, h, channels);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float* src = reinterpret_cast<const float*>(&values[size_t(h - 1 - y) * w + x]);
      std::copy(src, src + channels, img.at(x, y));
    }
  return img;
}

// Running mean over frames: the frames share settings, so equal weights are exact.
void accumulate(EyeImage& sum, const EyeImage& frame, int framesSoFar) {
  if (framesSoFar == 0) {
    sum = frame;
    return;
  }
  const float w = 1.0f / float(framesSoFar + 1);
  for (size_t i = 0; i < sum.color.size(); ++i) {
    sum.color[i] += (frame.color[i] - sum.color[i]) * w;
    sum.albedo[i] += (frame.albedo[i] - sum.albedo[i]) * w;
    sum.samples[i] += frame.samples[i];
  }
  sum.rays += frame.rays;
  sum.rejectedSamples += frame.rejectedSamples;
}

std::vector<std::string> writeEye(const EyeImage& e, const std::string& dir) {
  const std::vector<std::string> paths = {dir + "/color.exr", dir + "/albedo.exr",
                                          dir + "/normal.exr", dir + "/depth.exr"};
  writeImage(paths[0], toImage(e.color, e.width, e.height, 3));
  writeImage(paths[1], toImage(e.albedo, e.width, e.height, 3));
  writeImage(paths[2], toImage(e.normal, e.width, e.height, 3));
  writeImage(paths[3], toImage(e.depth, e.width, e.height, 1));
  return paths;
}

Image8 sideBySide(const std::vector<const EyeImage*>& eyes, float exposure) {
  const int w = eyes[0]->width, h = eyes[0]->height;
  Image8 out(w * int(eyes.size()), h, 3);
  for (size_t e = 0; e < eyes.size(); ++e)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const glm::u8vec3 c = displayColor(eyes[e]->color[size_t(h - 1 - y) * w + x], exposure);
        uint8_t* d = out.at(int(e) * w + x, y);
        d[0] = c.r, d[1] = c.g, d[2] = c.b;
      }
  return out;
}

}  // namespace

int renderPathTracedMode(const RenderRequest& r) {
  const auto t0 = Clock::now();
  const EmbreeScene embree(r.scene);
  const LightSet lights(r.scene);
  const double buildSeconds = secondsSince(t0);
  TraceSettings settings;
  settings.samplesPerPixel = r.spp;
  settings.maxBounces = r.bounces;
  settings.seed = r.seed;
  const TraceContext ctx{r.scene, embree, lights, settings};
  const int eyeCount = r.view.stereo ? 2 : 1;
  std::vector<EyeImage> sums(eyeCount);
  const auto t1 = Clock::now();
  uint64_t rays = 0;
  for (int f = 0; f < r.frames; ++f) {
    const auto eyes = eyeCameras(r.view, r.width, r.height, uint32_t(f));
    for (int e = 0; e < eyeCount; ++e) {
      const EyeImage img = renderPathTraced(ctx, eyes[e], uint32_t(e), uint32_t(f));
      rays += img.rays;
      accumulate(sums[e], img, f);
      const double done = double(f * eyeCount + e + 1) / (r.frames * eyeCount);
      const double elapsed = secondsSince(t1);
      reportProgress(done, rays / elapsed, elapsed * (1.0 - done) / done);
    }
  }
  const double traceSeconds = secondsSince(t1);
  std::vector<std::string> written;
  std::vector<const EyeImage*> eyePtrs;
  uint64_t rejected = 0;
  for (int e = 0; e < eyeCount; ++e) {
    for (const std::string& p : writeEye(sums[e], r.outDir + "/" + eyeFolder(r.view, e)))
      written.push_back(p);
    eyePtrs.push_back(&sums[e]);
    rejected += sums[e].rejectedSamples;
  }
  writeImage(r.outDir + "/color.png", sideBySide(eyePtrs, r.exposure));
  written.push_back(r.outDir + "/color.png");
  std::printf("scene %s: %zu triangles, %s\n", r.sceneSpec.c_str(),
              r.scene.instancedTriangleCount(), r.view.description.c_str());
  std::printf(
      "path traced %dx%d x %d eyes, %d spp x %d frames, %d bounces: BVH %.0f ms, trace %.2f s, "
      "%.2f Mrays/s, %llu samples rejected (NaN/Inf)\n",
      r.width, r.height, eyeCount, r.spp, r.frames, r.bounces, 1e3 * buildSeconds, traceSeconds,
      rays / traceSeconds * 1e-6, (unsigned long long)rejected);
  std::printf("wrote:\n");
  for (const std::string& p : written) std::printf("  %s\n", p.c_str());
  return 0;
}

}  // namespace photovr::app
