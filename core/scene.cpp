#include "core/scene.h"

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

bool TextureTransform::isIdentity() const {
  return offset == glm::vec2(0.0f) && rotation == 0.0f && scale == glm::vec2(1.0f);
}

bool Material::isEmissive() const {
  const glm::vec3 e = emission();
  return e.x > 0.0f || e.y > 0.0f || e.z > 0.0f;
}

size_t Scene::instancedTriangleCount() const {
  size_t n = 0;
  for (const Instance& inst : instances) n += meshes[inst.mesh].triangleCount();
  return n;
}

Bounds Scene::worldBounds() const {
  Bounds b;
  for (const Instance& inst : instances)
    for (const glm::vec3& p : meshes[inst.mesh].positions)
      b.extend(glm::vec3(inst.transform * glm::vec4(p, 1.0f)));
  return b;
}

}  // namespace photovr
