#include "core/skinning.h"

#include <cmath>

namespace photovr {

std::vector<glm::dmat4> skinningMatrices(const Skin& skin, const std::vector<glm::dmat4>& world) {
  std::vector<glm::dmat4> out(skin.joints.size(), glm::dmat4(1.0));
  for (size_t j = 0; j < skin.joints.size(); ++j) {
    const int node = skin.joints[j];
    if (node >= 0 && size_t(node) < world.size())
      out[j] = world[size_t(node)] * skin.inverseBind[j];
  }
  return out;
}

namespace {

glm::dmat4 blended(const MeshSkinning& s, size_t v, const std::vector<glm::dmat4>& matrices) {
  glm::dmat4 m(0.0);
  for (int k = 0; k < 4; ++k) {
    const double w = s.weights[v][k];
    if (w > 0.0) m += w * matrices[s.joints[v][k]];  // the loader checked every index
  }
  return m;
}

glm::vec3 unitOr(const glm::dvec3& v, const glm::vec3& fallback) {
  const double len = glm::length(v);
  return len > 0.0 && std::isfinite(len) ? glm::vec3(v / len) : fallback;
}

}  // namespace

void skinMesh(Mesh& mesh, const std::vector<glm::dmat4>& matrices) {
  const MeshSkinning& s = mesh.skinning;
  for (size_t v = 0; v < s.positions.size(); ++v) {
    const glm::dmat4 m = blended(s, v, matrices);
    mesh.positions[v] = glm::vec3(m * glm::dvec4(s.positions[v], 1.0));
    const glm::dmat3 linear(m);
    const double det = glm::determinant(linear);
    if (v < s.normals.size()) {
      const glm::dmat3 normalMatrix = det != 0.0 ? glm::transpose(glm::inverse(linear)) : linear;
      mesh.normals[v] = unitOr(normalMatrix * glm::dvec3(s.normals[v]), s.normals[v]);
    }
    if (v < s.tangents.size()) {
      const glm::vec4& t = s.tangents[v];
      mesh.tangents[v] = glm::vec4(unitOr(linear * glm::dvec3(t), glm::vec3(t)), t.w);
    }
  }
}

}  // namespace photovr
