#include "hybrid/hit_rebuild.h"

#include <new>
#include <type_traits>
#include <vector>

#include "trace/camera_lanes.h"

namespace photovr {
namespace {

static_assert(std::is_trivially_destructible_v<RebuiltHit>);  // built over in place below

RebuiltHit fromNamedHit(const Scene& scene, const NamedHit& h, const glm::vec3& direction) {
  return {surfaceAt(scene, h.hit, h.geometry, direction), direction, h.t, h.outside};
}

}  // namespace

RebuiltHit rebuildPrimaryHit(const Scene& scene, const VisibilityRecord& record,
                             const glm::vec3& origin, const glm::vec3& direction) {
  const NamedRay ray{{record.instance, record.triangle, record.b1, record.b2}, direction};
  return fromNamedHit(scene, namedHit(scene, origin, ray), direction);
}

uint64_t rebuildPrimaryHits(const Scene& scene, const MaterialTable& materials,
                            const gl::GBufferImage& g, const CameraRays& rays,
                            const glm::vec3& origin, size_t begin, size_t end,
                            std::span<RebuiltHit> hits) {
  thread_local std::vector<NamedRay> named;
  thread_local std::vector<NamedHit> out;
  thread_local std::vector<size_t> pixels;
  thread_local std::vector<glm::vec3> directions;
  named.resize(end - begin);
  pixels.resize(end - begin);
  directions.resize(end - begin);
  pixelRays(rays, begin, directions);
  size_t count = 0;
  for (size_t i = begin; i < end; ++i) {
    const VisibilityRecord rec = g.record(i);
    if (!rec.hit()) {  // the background: its ray alone is read (RebuiltHit{} was 168 bytes)
      hits[i - begin].direction = directions[i - begin];
      continue;
    }
    if (!isValidRecord(scene, rec)) {
      hits[i - begin] = RebuiltHit{};
      hits[i - begin].direction = directions[i - begin];
      continue;
    }
    // Field by field: a whole struct built on the stack and copied stalled on store
    // forwarding (a third of this loop's time in a profile).
    NamedRay& ray = named[count];
    ray.hit.instance = rec.instance;
    ray.hit.triangle = rec.triangle;
    ray.hit.b1 = rec.b1;
    ray.hit.b2 = rec.b2;
    ray.direction = directions[i - begin];
    pixels[count++] = i;
  }
  out.resize(count);
  namedHits(scene, origin, std::span(named).first(count), out);
  uint64_t outside = 0;
  for (size_t k = 0; k < count; ++k) {
    const NamedHit& h = out[k];
    // Built in place (the aggregate's prvalue member is not copied): assigning a returned
    // RebuiltHit copied 160 bytes through the stack.
    ::new (static_cast<void*>(&hits[pixels[k] - begin]))
        RebuiltHit{surfaceAt(scene, materials, h.hit, h.geometry, named[k].direction),
                   named[k].direction, h.t, h.outside};
    outside += h.outside;
  }
  return outside;
}

}  // namespace photovr
