// Primary hits rebuilt from the G-buffer's visibility record: the record names the instance
// and triangle; the pixel's own jittered ray is intersected with that one triangle from the
// scene's vertex data — the computation a ray tracer performs — so the hit is exact to float
// rounding and no precision is lost to depth-buffer reconstruction.
#pragma once

#include <cstdint>

#include "core/camera.h"
#include "core/scene.h"
#include "core/visibility.h"
#include "trace/surface.h"

namespace photovr {

struct RebuiltHit {
  SurfaceHit surface;
  float t = 0.0f;        // ray distance to the hit
  bool outside = false;  // the ray missed the named triangle (shared-edge disagreement)
};

// 'record' must be valid for 'scene'. Barycentrics of a ray that misses the triangle by a
// rounding error (raster and ray casting disagree on a shared edge) are clamped into it and
// the hit is flagged 'outside', so the disagreement is counted, not hidden.
RebuiltHit rebuildPrimaryHit(const Scene& scene, const VisibilityRecord& record,
                             const glm::vec3& origin, const glm::vec3& direction);

}  // namespace photovr
