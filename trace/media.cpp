#include "trace/media.h"

namespace photovr {

uint32_t MediumStack::outsideOf(uint32_t volume) const {
  for (int k = int(size) - 1; k >= 0; --k)
    if (instance[k] != volume) return instance[k];
  return kNone;
}

void MediumStack::enter(uint32_t volume) {
  if (size < kDepth) instance[size++] = volume;
}

void MediumStack::leave(uint32_t volume) {
  // The innermost entry of that volume; one left out of order (overlapping volumes) is
  // taken out where it is.
  for (int k = int(size) - 1; k >= 0; --k) {
    if (instance[k] != volume) continue;
    for (int j = k; j + 1 < int(size); ++j) instance[j] = instance[j + 1];
    --size;
    return;
  }
}

const Material* volumeMaterial(const Scene& scene, uint32_t instance) {
  if (instance == MediumStack::kNone) return nullptr;
  const Material& m = scene.materials[scene.meshes[scene.instances[instance].mesh].material];
  return m.thinWalled() ? nullptr : &m;
}

float mediumIor(const Scene& scene, uint32_t instance) {
  const Material* m = volumeMaterial(scene, instance);
  return m && m->ior > 0.0f ? m->ior : 1.0f;
}

glm::vec3 mediumAbsorption(const Scene& scene, uint32_t instance) {
  const Material* m = volumeMaterial(scene, instance);
  return m ? m->absorption() : glm::vec3(0.0f);
}

float relativeEta(const Scene& scene, const MediumStack& media, uint32_t instance, bool frontFace) {
  const float ior = mediumIor(scene, instance);
  return frontFace ? ior / mediumIor(scene, media.current())
                   : mediumIor(scene, media.outsideOf(instance)) / ior;
}

}  // namespace photovr
