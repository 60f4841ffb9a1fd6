#include "core/scene_transform.h"

namespace photovr {
namespace {

glm::vec3 moved(const glm::vec3& p, const glm::dvec3& offset) {
  return glm::vec3(glm::dvec3(p) + offset);
}

void moveTranslation(glm::mat4& m, const glm::dvec3& offset) {
  m[3] = glm::vec4(moved(glm::vec3(m[3]), offset), m[3][3]);
}

}  // namespace

void translateScene(Scene& scene, const glm::dvec3& offset) {
  for (Instance& i : scene.instances) {
    moveTranslation(i.transform, offset);
    moveTranslation(i.previousTransform, offset);
  }
  for (Light& l : scene.lights) l.position = moved(l.position, offset);
  for (Camera& c : scene.cameras) c.position = moved(c.position, offset);
}

Pose recenterOnView(Scene& scene, const Pose& view) {
  translateScene(scene, -glm::dvec3(view.position));
  return {glm::vec3(0.0f), view.orientation};
}

}  // namespace photovr
