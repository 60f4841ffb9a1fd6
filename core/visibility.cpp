#include "core/visibility.h"

namespace photovr {

WorldTriangle worldTriangle(const Scene& scene, uint32_t instance, uint32_t triangle) {
  const Instance& inst = scene.instances[instance];
  const Mesh& mesh = scene.meshes[inst.mesh];
  const uint32_t* idx = &mesh.indices[3 * size_t(triangle)];
  auto world = [&](uint32_t i) {
    return glm::vec3(inst.transform * glm::vec4(mesh.positions[i], 1.0f));
  };
  return {world(idx[0]), world(idx[1]), world(idx[2])};
}

bool isValidRecord(const Scene& scene, const VisibilityRecord& r) {
  if (r.instance >= scene.instances.size()) return false;
  return r.triangle < scene.meshes[scene.instances[r.instance].mesh].triangleCount();
}

glm::vec3 rebuildHitPoint(const Scene& scene, const VisibilityRecord& r) {
  const WorldTriangle t = worldTriangle(scene, r.instance, r.triangle);
  return t.p0 + r.b1 * (t.p1 - t.p0) + r.b2 * (t.p2 - t.p0);
}

}  // namespace photovr
