#include "harness/reference_cache.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/progress.h"
#include "trace/trace_output.h"
#include "core/files.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/scene_hash.h"
#include "trace/embree_scene.h"
#include "trace/lights.h"
#include "trace/path_tracer.h"

namespace photovr::harness {
namespace {

namespace fs = std::filesystem;
constexpr int kFramesPerChunk = 4;  // saved every 4 frames (16 spp)

std::string eyeFile(const std::string& dir, size_t e) {
  return dir + "/eye" + std::to_string(e) + ".exr";
}

std::vector<glm::vec3> fromImage(const ImageF& img) {  // top-down file -> bottom-up rows
  std::vector<glm::vec3> v(size_t(img.width) * img.height);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const float* p = img.at(x, img.height - 1 - y);
      v[size_t(y) * img.width + x] = glm::vec3(p[0], p[1], p[2]);
    }
  return v;
}

// The saved frame count; 0 (rebuild) for anything but a plausible count: the cache is a
// file a user or a crash can corrupt.
int cachedFrames(const std::string& dir) {
  std::ifstream in(dir + "/frames.txt");
  int frames = 0;
  return (in >> frames) && frames > 0 && frames <= (1 << 24) ? frames : 0;
}

void save(const Reference& ref, const ReferenceSpec& spec, int frames) {
  for (size_t e = 0; e < ref.eyes.size(); ++e)
    writeImage(eyeFile(ref.directory, e), toImage(ref.eyes[e], spec.width, spec.height));
  // The count is written last and atomically: a crash mid-save leaves the previous count,
  // and images with more samples than it says are still a valid (better) mean.
  writeFileAtomically(ref.directory + "/frames.txt", std::to_string(frames) + "\n");
}

bool load(Reference& ref, const ReferenceSpec& spec, int eyeCount, int frames) {
  try {
    for (int e = 0; e < eyeCount; ++e) {
      const ImageF img = readImageF(eyeFile(ref.directory, size_t(e)));
      if (img.width != spec.width || img.height != spec.height || img.channels < 3) return false;
      ref.eyes.push_back(fromImage(img));
    }
  } catch (const InputError&) {
    ref.eyes.clear();
    return false;
  }
  ref.samplesPerPixel = frames * kReferenceSppPerFrame;
  return true;
}

}  // namespace

std::string referenceCacheRoot() {
  if (const char* d = std::getenv("PHOTOVR_CACHE_DIR"); d && *d) return d;  // empty: unset
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/photovr";
  const char* home = std::getenv("HOME");
  return std::string(home ? home : ".") + "/.cache/photovr";
}

std::string referenceKey(const ReferenceSpec& s) {
  Hasher h;
  h.value(hashScene(*s.scene)).value(s.view.head.position).value(s.view.head.orientation);
  h.value(s.view.yfov).value(s.view.stereo).value(s.width).value(s.height).value(s.bounces);
  h.value(kReferenceSeed).value(kReferenceSppPerFrame);
  // How the samples were drawn: Sobol, each sample at its own place in the pixel (issue 18).
  // Caches made before say nothing, so they are not resumed with another sequence.
  h.text("sampler=sobol");
  return hexDigest(h.digest());
}

Reference loadOrRenderReference(const ReferenceSpec& spec, int spp) {
  Reference ref;
  ref.directory = referenceCacheRoot() + "/references/" + referenceKey(spec);
  fs::create_directories(ref.directory);
  const int eyeCount = spec.view.stereo ? 2 : 1;
  int frames = cachedFrames(ref.directory);
  if (frames > 0 && !load(ref, spec, eyeCount, frames)) frames = 0;
  const int targetFrames = (spp + kReferenceSppPerFrame - 1) / kReferenceSppPerFrame;
  if (frames >= targetFrames) return ref;
  std::fprintf(stderr, "photovr: reference %s: %d -> %d spp\n", ref.directory.c_str(),
               frames * kReferenceSppPerFrame, targetFrames * kReferenceSppPerFrame);
  const EmbreeScene embree(*spec.scene);
  const LightSet lights(*spec.scene);
  TraceSettings settings;
  settings.samplesPerPixel = kReferenceSppPerFrame;
  settings.maxBounces = spec.bounces;
  settings.seed = kReferenceSeed;
  const TraceContext ctx{*spec.scene, embree, lights, settings};
  std::vector<EyeImage> sums(eyeCount);
  for (int e = 0; e < eyeCount && frames > 0; ++e) {  // resume: the cached mean so far
    sums[e].color = ref.eyes[e];
    sums[e].samples.assign(ref.eyes[e].size(), 0);
  }
  const auto t0 = std::chrono::steady_clock::now();
  uint64_t rays = 0;
  for (int f = frames; f < targetFrames; ++f) {
    const auto eyes =
        eyeCameras(spec.view, spec.width, spec.height, uint32_t(f), ctx.settings.sampler);
    for (int e = 0; e < eyeCount; ++e) {
      const EyeImage img = renderPathTraced(ctx, eyes[e], uint32_t(e), uint32_t(f));
      rays += img.rays;
      accumulate(sums[e], img, f);
    }
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double done = double(f + 1 - frames) / (targetFrames - frames);
    reportProgress(done, rays / elapsed, elapsed * (1.0 - done) / done);
    if ((f + 1) % kFramesPerChunk == 0 || f + 1 == targetFrames) {
      ref.eyes.clear();
      for (const EyeImage& s : sums) ref.eyes.push_back(s.color);
      save(ref, spec, f + 1);
    }
  }
  ref.samplesPerPixel = targetFrames * kReferenceSppPerFrame;
  return ref;
}

}  // namespace photovr::harness
