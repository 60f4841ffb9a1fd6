// Primary hits alone, timed: the work the hybrid replaces with the G-buffer — traversal
// plus building each hit's SurfaceHit, which is what the hybrid's hit rebuild produces too,
// so the two stages compare like for like.
#pragma once

#include "core/camera.h"
#include "trace/embree_scene.h"
#include "trace/surface.h"

namespace photovr {

struct PrimaryRayStats {
  double milliseconds = 0.0;  // wall time of all primary rays of the eye, all threads
  uint64_t rays = 0, hits = 0;
};

// Casts one closest-hit ray per pixel through the camera's jittered samples, in parallel
// over the same tiles the path tracer uses, builds the surface hit, and discards it.
PrimaryRayStats timePrimaryRays(const Scene& scene, const EmbreeScene& embree,
                                const EyeCamera& camera);

}  // namespace photovr
