#include "core/mesh_util.h"

#include <cmath>

#include "core/error.h"

namespace photovr {
namespace {

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool finite(const glm::vec2& v) {
  return std::isfinite(v.x) && std::isfinite(v.y);
}

template <typename V>
void checkFinite(const std::vector<V>& values, const char* attribute, const std::string& where) {
  for (size_t i = 0; i < values.size(); ++i)
    if (!finite(values[i]))
      throw InputError(where,
                       std::string("non-finite ") + attribute + " at vertex " + std::to_string(i));
}

template <typename V>
void checkLength(const std::vector<V>& values, size_t n, const char* attribute,
                 const std::string& where) {
  if (!values.empty() && values.size() != n)
    throw InputError(where, std::string(attribute) + " has " + std::to_string(values.size()) +
                                " entries for " + std::to_string(n) + " vertices");
}

double triangleArea2(const Mesh& m, size_t t) {
  const glm::dvec3 a(m.positions[m.indices[3 * t]]);
  const glm::dvec3 b(m.positions[m.indices[3 * t + 1]]);
  const glm::dvec3 c(m.positions[m.indices[3 * t + 2]]);
  return glm::length(glm::cross(b - a, c - a));
}

}  // namespace

void validateMesh(const Mesh& mesh, const std::string& file) {
  const std::string where = file + ": mesh '" + mesh.name + "'";
  const size_t n = mesh.positions.size();
  if (n == 0) throw InputError(where, "has no vertices");
  checkLength(mesh.normals, n, "NORMAL", where);
  checkLength(mesh.uv0, n, "TEXCOORD_0", where);
  checkLength(mesh.uv1, n, "TEXCOORD_1", where);
  checkFinite(mesh.positions, "POSITION", where);
  checkFinite(mesh.normals, "NORMAL", where);
  checkFinite(mesh.uv0, "TEXCOORD_0", where);
  checkFinite(mesh.uv1, "TEXCOORD_1", where);
  if (mesh.indices.size() % 3 != 0)
    throw InputError(
        where, "index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3");
  for (size_t i = 0; i < mesh.indices.size(); ++i)
    if (mesh.indices[i] >= n)
      throw InputError(where, "index " + std::to_string(mesh.indices[i]) + " at position " +
                                  std::to_string(i) + " is out of range (" + std::to_string(n) +
                                  " vertices)");
  if (mesh.triangleCount() == 0) throw InputError(where, "has no triangles");
  if (degenerateTriangleCount(mesh) == mesh.triangleCount())
    throw InputError(where, "every triangle has zero area");
}

size_t degenerateTriangleCount(const Mesh& mesh) {
  size_t count = 0;
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const double a = triangleArea2(mesh, t);
    if (!(a > 0.0) || !std::isfinite(a)) ++count;
  }
  return count;
}

void computeVertexNormals(Mesh& mesh) {
  std::vector<glm::dvec3> acc(mesh.positions.size(), glm::dvec3(0.0));
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const uint32_t* i = &mesh.indices[3 * t];
    const glm::dvec3 a(mesh.positions[i[0]]), b(mesh.positions[i[1]]), c(mesh.positions[i[2]]);
    const glm::dvec3 n = glm::cross(b - a, c - a);  // length = 2 * area: area weighting
    for (int k = 0; k < 3; ++k) acc[i[k]] += n;
  }
  mesh.normals.resize(mesh.positions.size());
  for (size_t v = 0; v < acc.size(); ++v) {
    const double len = glm::length(acc[v]);
    mesh.normals[v] = len > 0.0 ? glm::vec3(acc[v] / len) : glm::vec3(0, 1, 0);
  }
}

template <typename T>
static void unshare(std::vector<T>& values, const std::vector<uint32_t>& indices) {
  if (values.empty()) return;
  std::vector<T> out(indices.size());
  for (size_t i = 0; i < indices.size(); ++i) out[i] = values[indices[i]];
  values.swap(out);
}

void makeFlatShaded(Mesh& mesh) {
  unshare(mesh.positions, mesh.indices);
  unshare(mesh.uv0, mesh.indices);
  unshare(mesh.uv1, mesh.indices);
  unshare(mesh.tangents, mesh.indices);
  unshare(mesh.skinning.joints, mesh.indices);
  unshare(mesh.skinning.weights, mesh.indices);
  for (size_t i = 0; i < mesh.indices.size(); ++i) mesh.indices[i] = uint32_t(i);
  mesh.normals.assign(mesh.positions.size(), glm::vec3(0, 1, 0));
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const glm::dvec3 a(mesh.positions[3 * t]), b(mesh.positions[3 * t + 1]),
        c(mesh.positions[3 * t + 2]);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double len = glm::length(n);
    const glm::vec3 fn = len > 0.0 ? glm::vec3(n / len) : glm::vec3(0, 1, 0);
    for (int k = 0; k < 3; ++k) mesh.normals[3 * t + k] = fn;
  }
}

void computeTangents(Mesh& mesh) {
  const size_t n = mesh.positions.size();
  if (mesh.uv0.size() != n) return;
  std::vector<glm::dvec3> tan(n, glm::dvec3(0.0)), bit(n, glm::dvec3(0.0));
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const uint32_t* i = &mesh.indices[3 * t];
    const glm::dvec3 e1 = glm::dvec3(mesh.positions[i[1]]) - glm::dvec3(mesh.positions[i[0]]);
    const glm::dvec3 e2 = glm::dvec3(mesh.positions[i[2]]) - glm::dvec3(mesh.positions[i[0]]);
    const glm::dvec2 d1 = glm::dvec2(mesh.uv0[i[1]]) - glm::dvec2(mesh.uv0[i[0]]);
    const glm::dvec2 d2 = glm::dvec2(mesh.uv0[i[2]]) - glm::dvec2(mesh.uv0[i[0]]);
    const double det = d1.x * d2.y - d2.x * d1.y;
    if (std::abs(det) < 1e-20) continue;
    const double r = 1.0 / det;
    const glm::dvec3 s = (e1 * d2.y - e2 * d1.y) * r;
    const glm::dvec3 u = (e2 * d1.x - e1 * d2.x) * r;
    for (int k = 0; k < 3; ++k) {
      tan[i[k]] += s;
      bit[i[k]] += u;
    }
  }
  mesh.tangents.resize(n);
  for (size_t v = 0; v < n; ++v) {
    const glm::dvec3 nn(mesh.normals[v]);
    glm::dvec3 t = tan[v] - nn * glm::dot(nn, tan[v]);
    double len = glm::length(t);
    if (!(len > 1e-20)) {  // no usable uv gradient: any vector perpendicular to n
      t = std::abs(nn.x) < 0.9 ? glm::cross(nn, glm::dvec3(1, 0, 0))
                               : glm::cross(nn, glm::dvec3(0, 1, 0));
      len = glm::length(t);
    }
    t /= len;
    const double w = glm::dot(glm::cross(nn, t), bit[v]) < 0.0 ? -1.0 : 1.0;
    mesh.tangents[v] = glm::vec4(glm::vec3(t), float(w));
  }
}

}  // namespace photovr
