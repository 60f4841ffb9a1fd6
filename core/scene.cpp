#include "core/scene.h"

#include <algorithm>
#include <cmath>

namespace photovr {

glm::mat3 TextureTransform::matrix() const {
  // KHR_texture_transform: translation * rotation * scale, rotation as the extension's
  // reference implementation writes it (counter-clockwise, uv space with v down).
  // Unrotated transforms (the common scale/offset case) skip cos/sin: the tracer calls this
  // per texture sample (sincos was 1 % of an atrium render). cos(0) = 1, sin(0) = 0 exactly.
  const float c = rotation == 0.0f ? 1.0f : std::cos(rotation);
  const float s = rotation == 0.0f ? 0.0f : std::sin(rotation);
  const glm::mat3 t(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);
  const glm::mat3 r(c, -s, 0, s, c, 0, 0, 0, 1);
  const glm::mat3 sc(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
  return t * r * sc;
}

bool Material::isEmissive() const {
  if (unlit) return false;  // its radiance is its base colour, and it is no light
  const glm::vec3 e = emission();
  return e.x > 0.0f || e.y > 0.0f || e.z > 0.0f;
}

bool Material::textured() const {
  for (const TextureRef* slot : textureSlots())
    if (slot->valid()) return true;
  return false;
}

float Material::iorF0() const {
  const double r = (double(ior) - 1.0) / (double(ior) + 1.0);
  return float(r * r);
}

glm::vec3 Material::absorption() const {
  if (thinWalled() || !(attenuationDistance > 0.0f)) return glm::vec3(0.0f);
  glm::vec3 sigma;
  // A colour of 0 would be an infinite coefficient: 1e-6 of the light survives one
  // attenuation distance instead, absorbing everything in practice.
  for (int c = 0; c < 3; ++c)
    sigma[c] = -std::log(std::max(attenuationColor[c], 1e-6f)) / attenuationDistance;
  return sigma;
}

size_t Scene::instancedTriangleCount() const {
  size_t n = 0;
  for (const Instance& inst : instances)
    if (hasMesh(inst.mesh)) n += meshes[inst.mesh].triangleCount();
  return n;
}

Bounds Scene::worldBounds() const {
  Bounds b;
  // An instance naming a mesh that does not exist is skipped (analyzeScene warns about it):
  // the bounds of a broken scene are those of what can be drawn.
  for (const Instance& inst : instances) {
    if (!hasMesh(inst.mesh)) continue;
    for (const glm::vec3& p : meshes[inst.mesh].positions)
      b.extend(glm::vec3(inst.transform * glm::vec4(p, 1.0f)));
  }
  return b;
}

}  // namespace photovr
