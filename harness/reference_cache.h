// Converged path-traced references, cached by scene content and render settings, so that
// `ab` and the benches compare against the same image and a long render is paid once.
// Accumulation is resumable and can be split into jobs: frames are accumulated in shards
// (reference_shards.h), each saved atomically every few frames; merging a complete set
// gives the same reference, bit for bit, however it was split.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/view.h"
#include "core/scene.h"
#include "harness/reference_shards.h"

namespace photovr::harness {

struct ReferenceSpec {
  const Scene* scene = nullptr;
  View view;
  int width = 0, height = 0, bounces = 8;
};

struct Reference {
  std::vector<std::vector<glm::vec3>> eyes;  // mean radiance per eye, rows bottom-up
  int samplesPerPixel = 0;
  std::string directory;
  double estimatedRelMse = 0.0;  // of the mean, from the frames' spread (when merged now)
};

// Cache root: $PHOTOVR_CACHE_DIR, else $XDG_CACHE_HOME/photovr, else ~/.cache/photovr.
std::string referenceCacheRoot();
std::string referenceKey(const ReferenceSpec& spec);

// Loads the cached reference and renders more samples until it has at least 'spp' per
// pixel (as shard 0/1, reference_shards.h; a complete set of other jobs' shards is merged
// instead). Progress goes to stderr.
Reference loadOrRenderReference(const ReferenceSpec& spec, int spp);

// One job of a sharded reference: renders shard 'shard''s share of the frames 'spp' needs,
// then merges when every shard of its count is there. 'complete' says whether it did.
struct ShardResult {
  Reference reference;  // the merged reference when complete
  bool complete = false;
};
ShardResult renderReferenceShard(const ReferenceSpec& spec, int spp, const ShardId& shard);

// Independent of the seeds users pass (default 0), so a reference's noise never
// correlates with the image it judges.
constexpr uint32_t kReferenceSeed = 0x5eed5eedu;
constexpr int kReferenceSppPerFrame = 4;

}  // namespace photovr::harness
