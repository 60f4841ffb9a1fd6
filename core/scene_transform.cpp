#include "core/scene_transform.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

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
  scene.origin -= offset;
  // A skinned mesh's vertices stay in the old coordinates until its next pose, which must
  // then skin its previous positions anew rather than keep these.
  for (Mesh& m : scene.meshes) m.skinning.posedAt = std::numeric_limits<double>::quiet_NaN();
}

bool floatsTooCoarse(double reach, double extent, double fraction) {
  if (!(reach > 0.0) || !(extent > 0.0) || !std::isfinite(reach)) return false;
  const float r = float(std::min(reach, double(std::numeric_limits<float>::max())));
  const double spacing = double(std::nextafter(r, INFINITY)) - double(r);
  return spacing > fraction * extent;
}

namespace {

// Re-based when floats there are coarser than this share of the scene's extent: 16x finer
// than where the snapping became visible (scene_info's warning, 1/4096), about where a
// scene at the origin has them (2^-23 x its reach) times 128.
constexpr double kRebaseFraction = 1.0 / 65536.0;

struct DoubleBounds {
  glm::dvec3 min{std::numeric_limits<double>::infinity()};
  glm::dvec3 max{-std::numeric_limits<double>::infinity()};
};

DoubleBounds boundsOf(const Scene& scene, const DoublePlacement& placed) {
  DoubleBounds b;
  for (size_t i = 0; i < scene.instances.size() && i < placed.instances.size(); ++i) {
    if (!scene.hasMesh(scene.instances[i].mesh)) continue;
    for (const glm::vec3& p : scene.meshes[size_t(scene.instances[i].mesh)].positions) {
      const glm::dvec3 w(placed.instances[i] * glm::dvec4(glm::dvec3(p), 1.0));
      b.min = glm::min(b.min, w);
      b.max = glm::max(b.max, w);
    }
  }
  return b;
}

bool withinFloatRange(const glm::dvec3& p) {
  const double limit = double(std::numeric_limits<float>::max());
  return glm::all(glm::lessThan(glm::abs(p), glm::dvec3(limit)));
}

}  // namespace

bool storePlacement(Scene& scene, const DoublePlacement& placed) {
  const DoubleBounds b = boundsOf(scene, placed);
  glm::dvec3 origin(0.0);
  if (b.min.x <= b.max.x) {
    if (!withinFloatRange(b.min) || !withinFloatRange(b.max)) return false;
    const glm::dvec3 reach = glm::max(glm::abs(b.min), glm::abs(b.max));
    if (floatsTooCoarse(std::max({reach.x, reach.y, reach.z}), glm::length(b.max - b.min),
                        kRebaseFraction))
      origin = 0.5 * (b.min + b.max);
  }
  const glm::dmat4 toScene = glm::translate(glm::dmat4(1.0), -origin);
  for (size_t i = 0; i < scene.instances.size() && i < placed.instances.size(); ++i)
    scene.instances[i].transform = scene.instances[i].previousTransform =
        glm::mat4(toScene * placed.instances[i]);
  for (size_t i = 0; i < scene.lights.size() && i < placed.lights.size(); ++i)
    scene.lights[i].position = glm::vec3(placed.lights[i] - origin);
  for (size_t i = 0; i < scene.cameras.size() && i < placed.cameras.size(); ++i)
    scene.cameras[i].position = glm::vec3(placed.cameras[i] - origin);
  scene.origin = origin;
  return true;
}

Pose recenterOnView(Scene& scene, const Pose& view) {
  translateScene(scene, -glm::dvec3(view.position));
  return {glm::vec3(0.0f), view.orientation};
}

}  // namespace photovr
