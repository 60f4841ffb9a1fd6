// The least a path tracer computes at a hit, as shaders for EmbreeScene::replay: what
// photovr_bench_trace's "floor" columns add to bare traversal (issue 20).
//
// shadeLambert: the scene taken as Lambert-only with each material's constant base colour,
// lit by one point light seen without a shadow ray. Per hit: the world position and unit
// normal facing the ray, an orthonormal frame, two random numbers, a cosine-weighted bounce
// direction, the offset origin and the light's unshadowed contribution. No textures,
// normal maps, GGX, Fresnel, MIS, light choice, environment, Russian roulette or path
// state: floor/raw is what a tracer that shades as little as that reaches.
//
// shadeBsdf: the same with photovr's own BSDF in place of Lambert (trace/bsdf.h, each
// material's constant factors): prepareBsdf, evalBsdfAndPdf towards the light and
// sampleBsdf for the bounce, as photovr runs them at every vertex. What the thesis's
// GGX/Smith/Schlick + Lambert model costs on its own, before textures, light sampling,
// MIS and the path's bookkeeping.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "trace/bsdf.h"
#include "trace/embree_scene.h"

namespace photovr {

class ShadingFloor {
 public:
  explicit ShadingFloor(const Scene& scene);
  // ReplayHitShaders; 'user' is a ShadingFloor.
  static float shadeLambert(const void* user, const RecordedRay& ray, const ReplayHit& hit,
                            uint64_t index);
  static float shadeBsdf(const void* user, const RecordedRay& ray, const ReplayHit& hit,
                         uint64_t index);

 private:
  // What both shaders compute first: the unit normal facing the ray, the offset origin of
  // the next rays and the direction and squared distance to the light.
  struct HitFrame {
    glm::vec3 n, origin, toLight;
    float distance2;
  };
  HitFrame frameAt(const RecordedRay& ray, const ReplayHit& hit) const;

  std::vector<glm::mat3> normalToWorld_;  // per instance: instance-space normals to world
  std::vector<BsdfParams> bsdf_;          // per instance: its material's constant factors
  glm::vec3 light_{0.0f, 2.0f, 0.0f};     // where the point light is (its cost, not its look)
};

}  // namespace photovr
