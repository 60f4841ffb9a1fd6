#include "bench/shading_floor.h"

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

ShadingFloor::ShadingFloor(const Scene& scene) {
  for (const Instance& inst : scene.instances) {
    const glm::mat3 m(inst.transform);
    normalToWorld_.push_back(
        glm::mat3(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1])));
    const Material& mat = scene.materials[size_t(scene.meshes[size_t(inst.mesh)].material)];
    BsdfParams p;
    p.baseColor = glm::vec3(mat.baseColorFactor);
    p.metallic = mat.metallicFactor;
    p.roughness = mat.roughnessFactor;
    bsdf_.push_back(p);
  }
}

ShadingFloor::HitFrame ShadingFloor::frameAt(const RecordedRay& ray, const ReplayHit& hit) const {
  HitFrame f;
  const glm::vec3 p = ray.origin + ray.dir * hit.t;
  f.n = glm::normalize(hit.instanced ? normalToWorld_[hit.instance] * hit.ng : hit.ng);
  if (glm::dot(f.n, ray.dir) > 0.0f) f.n = -f.n;
  f.origin = p + f.n * (1e-4f * (1.0f + glm::length(p)));
  f.toLight = light_ - f.origin;
  f.distance2 = glm::dot(f.toLight, f.toLight);
  return f;
}

float ShadingFloor::shadeLambert(const void* user, const RecordedRay& ray, const ReplayHit& hit,
                                 uint64_t index) {
  const auto& floor = *static_cast<const ShadingFloor*>(user);
  const HitFrame f = floor.frameAt(ray, hit);
  glm::vec3 t, b;
  orthonormalBasis(f.n, t, b);  // the tracer's (Duff et al. 2017)
  // Cosine-weighted hemisphere by Malley's method: a uniform disc point lifted.
  const glm::vec2 u = twoNumbers(index);
  const float r = std::sqrt(u.x), phi = 6.28318531f * u.y;
  const glm::vec3 wi = t * (r * std::cos(phi)) + b * (r * std::sin(phi)) +
                       f.n * std::sqrt(std::max(0.0f, 1.0f - u.x));
  const float cosLight = std::max(0.0f, glm::dot(f.n, f.toLight)) / std::sqrt(f.distance2);
  const glm::vec3 direct =
      floor.bsdf_[hit.instance].baseColor * (cosLight / (3.14159265f * f.distance2));
  return direct.r + direct.g + direct.b + wi.x + f.origin.y;
}

float ShadingFloor::shadeBsdf(const void* user, const RecordedRay& ray, const ReplayHit& hit,
                              uint64_t index) {
  const auto& floor = *static_cast<const ShadingFloor*>(user);
  const HitFrame f = floor.frameAt(ray, hit);
  const Frame frame = Frame::fromZ(f.n);
  const BsdfVertex v = prepareBsdf(floor.bsdf_[hit.instance], frame.toLocal(-ray.dir));
  const float distance = std::sqrt(f.distance2);
  const glm::vec3 wiLight = frame.toLocal(f.toLight / distance);
  const BsdfEval e = evalBsdfAndPdf(v, wiLight);
  const glm::vec3 direct = e.f.total() * (std::max(0.0f, wiLight.z) / f.distance2);
  const BsdfSample bounce = sampleBsdf(v, twoNumbers(index));
  const glm::vec3 wi = frame.toWorld(bounce.wi);
  return direct.r + direct.g + direct.b + bounce.weight.r + wi.x + f.origin.y;
}

}  // namespace photovr
