// How the tracer lays out a scene's BVHs (trace/embree_scene.cpp), decided from the scene
// alone, so that `photovr info` says it too: two levels (each mesh's BVH, instanced by a top
// level), or one (every instance's mesh copied into world space in a single BVH).
#pragma once

#include "core/scene.h"

namespace photovr {

// One level while the copies hold at most this many times the triangles the instanced
// meshes store: up to tenfold, one level traced 3-6 % faster than two on spheres' meshes
// copied, but built 7-28x slower, and atrium's small meshes under 435 instances (41-fold)
// traced 7 % slower flattened (docs/MEASUREMENTS.md, "Shared meshes copied").
constexpr double kOneLevelCopies = 2.0;

struct BvhLayout {
  bool moves = false;     // animated (instances move) or skinned (vertices move): two levels
  double copies = 1.0;    // triangles the instances hold over those their meshes store
  bool oneLevel = false;  // still, some instance, and copies <= kOneLevelCopies
};

BvhLayout bvhLayoutOf(const Scene& scene);

}  // namespace photovr
