#include "hybrid/hit_rebuild.h"

#include <algorithm>

namespace photovr {

RebuiltHit rebuildPrimaryHit(const Scene& scene, const VisibilityRecord& record,
                             const glm::vec3& origin, const glm::vec3& direction) {
  RebuiltHit r;
  const WorldTriangle tri = worldTriangle(scene, record.instance, record.triangle);
  float t = 0.0f, b1 = record.b1, b2 = record.b2;
  if (!intersectTriangle(origin, direction, tri, t, b1, b2)) {
    // Seen exactly edge-on: keep the rasterizer's barycentrics.
    b1 = record.b1;
    b2 = record.b2;
    r.outside = true;
  }
  if (b1 < 0.0f || b2 < 0.0f || b1 + b2 > 1.0f) {
    r.outside = true;
    b1 = std::max(b1, 0.0f);
    b2 = std::max(b2, 0.0f);
    const float sum = b1 + b2;
    if (sum > 1.0f) b1 /= sum, b2 /= sum;
  }
  // The triangle's world corners, once: its geometry comes from them too.
  const HitRef ref{record.instance, record.triangle, b1, b2};
  r.surface = surfaceAt(scene, ref, hitGeometry(tri, b1, b2), direction);
  r.t = glm::dot(r.surface.position - origin, direction);
  return r;
}

}  // namespace photovr
