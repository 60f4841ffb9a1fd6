#include "core/bvh_layout.h"

#include <vector>

#include "core/animation.h"

namespace photovr {

BvhLayout bvhLayoutOf(const Scene& scene) {
  BvhLayout l;
  l.moves = isAnimated(scene);
  std::vector<uint8_t> used(scene.meshes.size(), 0);
  size_t instanced = 0, stored = 0;
  for (const Instance& inst : scene.instances) {
    if (!scene.hasMesh(inst.mesh)) continue;
    const Mesh& mesh = scene.meshes[size_t(inst.mesh)];
    l.moves |= mesh.skinned();
    instanced += mesh.triangleCount();
    if (!used[size_t(inst.mesh)]++) stored += mesh.triangleCount();
  }
  l.copies = stored > 0 ? double(instanced) / double(stored) : 1.0;
  l.oneLevel = !l.moves && !scene.instances.empty() && l.copies <= kOneLevelCopies;
  return l;
}

}  // namespace photovr
