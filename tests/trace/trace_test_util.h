// Small hand-built scenes for tracer tests.
#pragma once

#include <glm/gtc/matrix_transform.hpp>

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

}  // namespace photovr::testing
