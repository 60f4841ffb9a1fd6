// Small hand-built scenes for tracer tests.
#pragma once

#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/camera.h"
#include "core/scene.h"

namespace photovr::testing {

// Square of side 2 * half in the plane z = 0, facing +Z (counter-clockwise seen from +Z).
inline Mesh squareMesh(float half, int material) {
  Mesh m;
  m.name = "square";
  m.positions = {{-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}};
  m.normals.assign(4, glm::vec3(0, 0, 1));
  m.uv0 = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.material = material;
  return m;
}

inline Material diffuseMaterial(glm::vec3 color) {
  Material m;
  m.baseColorFactor = glm::vec4(color, 1.0f);
  m.metallicFactor = 0.0f;
  m.roughnessFactor = 1.0f;
  return m;
}

inline int addSquare(Scene& s, float half, int material, const glm::mat4& transform) {
  s.meshes.push_back(squareMesh(half, material));
  s.instances.push_back({int(s.meshes.size()) - 1, transform, transform, "square"});
  return int(s.instances.size()) - 1;
}

// An eye camera of odd size (37-86 x 30-89: runs of pixels cross rows and end off groups of
// eight), an asymmetric field, a sub-pixel jitter, placed within 1 of the origin and turned
// by a random quaternion whose real part is 'facing' (0: any way; larger: nearer -Z).
inline EyeCamera randomEyeCamera(std::mt19937& rng, float facing) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  EyeCamera c;
  c.width = 37 + int(rng() % 50);
  c.height = 30 + int(rng() % 60);
  c.fov = {1.0f + 0.4f * u(rng), 1.0f + 0.4f * u(rng), 1.2f + 0.3f * u(rng), 1.0f + 0.3f * u(rng)};
  c.jitter = glm::vec2(0.5f * u(rng), 0.5f * u(rng));
  c.pose.position = glm::vec3(u(rng), u(rng), u(rng));
  const float w = facing > 0.0f ? facing : u(rng);
  c.pose.orientation = glm::normalize(glm::quat(w, u(rng), u(rng), u(rng)));
  return c;
}

}  // namespace photovr::testing
