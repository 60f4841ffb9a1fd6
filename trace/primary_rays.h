// Primary rays alone, timed: the traversal work the hybrid replaces with the G-buffer.
#pragma once

#include "core/camera.h"
#include "trace/embree_scene.h"

namespace photovr {

struct PrimaryRayStats {
  double milliseconds = 0.0;  // wall time of all primary rays of the eye, all threads
  uint64_t rays = 0, hits = 0;
};

// Casts one closest-hit ray per pixel through the camera's jittered samples, in parallel
// over the same tiles the path tracer uses, and discards the hits.
PrimaryRayStats timePrimaryRays(const EmbreeScene& embree, const EyeCamera& camera);

}  // namespace photovr
