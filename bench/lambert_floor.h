// The least a path tracer computes at a hit, as a shader for EmbreeScene::replay: what
// photovr_bench_trace's "floor" column adds to bare traversal. The scene is taken as
// Lambert-only with each material's constant base colour, lit by one point light seen
// without a shadow ray; per hit: the world position and unit normal facing the ray, an
// orthonormal frame, two random numbers, a cosine-weighted bounce direction, the offset
// origin and the light's unshadowed contribution. No textures, normal maps, GGX, Fresnel,
// MIS, light choice, environment, Russian roulette or path state: the floor under any
// tracer of the same rays, so floor/raw bounds what photovr/raw can reach (issue 20).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "trace/embree_scene.h"

namespace photovr {

class LambertFloor {
 public:
  explicit LambertFloor(const Scene& scene);
  // A ReplayHitShader; 'user' is a LambertFloor.
  static float shade(const void* user, const RecordedRay& ray, const ReplayHit& hit,
                     uint64_t index);

 private:
  std::vector<glm::mat3> normalToWorld_;  // per instance: instance-space normals to world
  std::vector<glm::vec3> albedo_;         // per instance: its material's base colour
  glm::vec3 light_{0.0f, 2.0f, 0.0f};     // where the point light is (its cost, not its look)
};

}  // namespace photovr
