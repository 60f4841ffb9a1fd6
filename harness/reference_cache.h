// Converged path-traced references, cached by scene content and render settings, so that
// `ab` and the benches compare against the same image and a long render is paid once.
// Accumulation is resumable: every chunk of frames is saved (atomically) with its count,
// and a later call continues from there without losing samples.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/view.h"
#include "core/scene.h"

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
};

// Cache root: $PHOTOVR_CACHE_DIR, else $XDG_CACHE_HOME/photovr, else ~/.cache/photovr.
std::string referenceCacheRoot();
std::string referenceKey(const ReferenceSpec& spec);

// Loads the cached reference and renders more samples until it has at least 'spp' per
// pixel. Progress goes to stderr.
Reference loadOrRenderReference(const ReferenceSpec& spec, int spp);

// Independent of the seeds users pass (default 0), so a reference's noise never
// correlates with the image it judges.
constexpr uint32_t kReferenceSeed = 0x5eed5eedu;
constexpr int kReferenceSppPerFrame = 4;

}  // namespace photovr::harness
