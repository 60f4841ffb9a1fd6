#include "bench/lambert_floor.h"

#include <algorithm>
#include <cmath>

#include "trace/sampling.h"

namespace photovr {
namespace {

// Two numbers in [0, 1) from one 64-bit hash of the ray's index (splitmix64's finaliser).
glm::vec2 twoNumbers(uint64_t index) {
  uint64_t z = index + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return {float(uint32_t(z) >> 8) * 0x1p-24f, float(uint32_t(z >> 32) >> 8) * 0x1p-24f};
}

}  // namespace

LambertFloor::LambertFloor(const Scene& scene) {
  for (const Instance& inst : scene.instances) {
    const glm::mat3 m(inst.transform);
    normalToWorld_.push_back(
        glm::mat3(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1])));
    const Material& mat = scene.materials[size_t(scene.meshes[size_t(inst.mesh)].material)];
    albedo_.push_back(glm::vec3(mat.baseColorFactor));
  }
}

float LambertFloor::shade(const void* user, const RecordedRay& ray, const ReplayHit& hit,
                          uint64_t index) {
  const auto& f = *static_cast<const LambertFloor*>(user);
  const glm::vec3 p = ray.origin + ray.dir * hit.t;
  glm::vec3 n = glm::normalize(f.normalToWorld_[hit.instance] * hit.ng);
  if (glm::dot(n, ray.dir) > 0.0f) n = -n;
  glm::vec3 t, b;
  orthonormalBasis(n, t, b);  // the tracer's (Duff et al. 2017)
  // Cosine-weighted hemisphere by Malley's method: a uniform disc point lifted.
  const glm::vec2 u = twoNumbers(index);
  const float r = std::sqrt(u.x), phi = 6.28318531f * u.y;
  const glm::vec3 wi =
      t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0f, 1.0f - u.x));
  const glm::vec3 origin = p + n * (1e-4f * (1.0f + glm::length(p)));
  const glm::vec3 toLight = f.light_ - origin;
  const float d2 = glm::dot(toLight, toLight);
  const float cosLight = std::max(0.0f, glm::dot(n, toLight)) / std::sqrt(d2);
  const glm::vec3 direct = f.albedo_[hit.instance] * (cosLight / (3.14159265f * d2));
  return direct.r + direct.g + direct.b + wi.x + origin.y;
}

}  // namespace photovr
