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
#include "harness/reference_shards.h"
#include "trace/caustics.h"
#include "trace/embree_scene.h"
#include "trace/lights.h"
#include "trace/path_tracer.h"

namespace photovr::harness {
namespace {

namespace fs = std::filesystem;
constexpr int kFramesPerChunk = 4;  // a shard is saved every 4 of its frames (16 spp)

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

// The merged reference's frame count; 0 (none) for anything but a plausible count: the
// cache is a file a user or a crash can corrupt.
int cachedFrames(const std::string& dir) {
  std::ifstream in(dir + "/frames.txt");
  int frames = 0;
  return (in >> frames) && frames > 0 && frames <= (1 << 24) ? frames : 0;
}

// The merged mean as the cache keeps it for readers (ab, benches): one EXR per eye, then
// the frame count, written last and atomically. Every merge of the same frames writes the
// same bits, so two jobs merging at once leave the same files.
void saveMerged(const Reference& ref, const ReferenceSpec& spec, int frames) {
  for (size_t e = 0; e < ref.eyes.size(); ++e)
    writeImage(eyeFile(ref.directory, e), toImage(ref.eyes[e], spec.width, spec.height));
  writeFileAtomically(ref.directory + "/frames.txt", std::to_string(frames) + "\n");
}

bool loadMerged(Reference& ref, const ReferenceSpec& spec, int eyeCount, int frames) {
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

int eyeCountOf(const ReferenceSpec& spec) {
  return spec.view.stereo ? 2 : 1;
}

int framesFor(int spp) {
  return (spp + kReferenceSppPerFrame - 1) / kReferenceSppPerFrame;
}

std::string directoryOf(const ReferenceSpec& spec) {
  const std::string dir = referenceCacheRoot() + "/references/" + referenceKey(spec);
  fs::create_directories(dir);
  return dir;
}

// A complete set of shards of one of 'counts' holding at least 'frames' frames, merged and
// saved as the cache's reference.
bool mergeAny(Reference& ref, const ReferenceSpec& spec, int frames,
              const std::vector<int>& counts) {
  const int eyes = eyeCountOf(spec);
  for (int count : counts) {
    std::optional<MergedReference> m =
        mergeShards(ref.directory, count, spec.width, spec.height, eyes);
    if (!m || m->frames < frames) continue;
    ref.eyes = std::move(m->eyes);
    ref.samplesPerPixel = m->frames * kReferenceSppPerFrame;
    ref.estimatedRelMse = m->estimatedRelMse;
    saveMerged(ref, spec, m->frames);
    return true;
  }
  return false;
}

// Renders shard 'id''s share of frames [0, frames), resuming from its file.
void renderShard(const ReferenceSpec& spec, const std::string& dir, const ShardId& id, int frames) {
  const int eyes = eyeCountOf(spec);
  ShardSums sums = loadShard(dir, id, spec.width, spec.height, eyes)
                       .value_or(ShardSums(id, spec.width, spec.height, eyes));
  const int share = framesOfShard(id, frames);
  if (sums.frames >= share) return;
  std::fprintf(stderr, "photovr: reference %s, shard %d/%d: %d -> %d spp\n", dir.c_str(), id.index,
               id.count, sums.frames * kReferenceSppPerFrame, share * kReferenceSppPerFrame);
  const EmbreeScene embree(*spec.scene);
  const LightSet lights(*spec.scene);
  TraceSettings settings;
  settings.samplesPerPixel = kReferenceSppPerFrame;
  settings.maxBounces = spec.bounces;
  settings.seed = kReferenceSeed;
  settings.caustics = true;  // see referenceKey
  const TraceContext ctx{*spec.scene, embree, lights, settings};
  const auto t0 = std::chrono::steady_clock::now();
  const int first = sums.frames;
  uint64_t rays = 0;
  for (int i = first; i < share; ++i) {
    const uint32_t f = uint32_t(id.index + i * id.count);
    const auto cams = eyeCameras(spec.view, spec.width, spec.height, f, ctx.settings.sampler);
    for (int e = 0; e < eyes; ++e) {
      const EyeImage img = renderPathTraced(ctx, cams[e], uint32_t(e), f);
      rays += img.rays;
      sums.add(e, img.color);
    }
    sums.frameDone();
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double done = double(i + 1 - first) / (share - first);
    reportProgress(done, rays / elapsed, elapsed * (1.0 - done) / done);
    if ((i + 1) % kFramesPerChunk == 0 || i + 1 == share) saveShard(dir, sums);
  }
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
  // Accumulated in shards of fixed-point sums (reference_shards.h); caches made before keep
  // a float running mean, which is not resumed.
  h.text("accumulation=shards-fixed32");
  // Directional lights' caustics light-traced (trace/caustics.h): the same image, converged
  // far sooner where the sun shines through smooth surfaces; caches made before are not
  // resumed there. Scenes without such caustics keep their key (their images do not change).
  if (hasLightTracedCaustics(*s.scene)) h.text("caustics=light-traced, a path per 8 samples");
  return hexDigest(h.digest());
}

Reference loadOrRenderReference(const ReferenceSpec& spec, int spp) {
  Reference ref;
  ref.directory = directoryOf(spec);
  const int frames = framesFor(spp);
  const int cached = cachedFrames(ref.directory);
  if (cached >= frames && loadMerged(ref, spec, eyeCountOf(spec), cached)) return ref;
  ref.eyes.clear();
  if (mergeAny(ref, spec, frames, shardCountsIn(ref.directory)))
    return ref;  // shards of earlier jobs, complete
  renderShard(spec, ref.directory, {0, 1}, frames);
  if (!mergeAny(ref, spec, frames, {1}))
    throw InputError(ref.directory, "the reference's shard 0/1 does not merge (cache changed?)");
  return ref;
}

ShardResult renderReferenceShard(const ReferenceSpec& spec, int spp, const ShardId& shard) {
  ShardResult r;
  r.reference.directory = directoryOf(spec);
  const int frames = framesFor(spp);
  renderShard(spec, r.reference.directory, shard, frames);
  r.complete = mergeAny(r.reference, spec, frames, {shard.count});
  return r;
}

}  // namespace photovr::harness
