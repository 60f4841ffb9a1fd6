#include "core/mesh_gen.h"

#include <cassert>
#include <cmath>

#include <glm/gtc/matrix_inverse.hpp>

namespace photovr {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Vertex {
  glm::dvec3 position;
  glm::dvec3 normal;
  glm::dvec2 uv;
};

uint32_t addVertex(Mesh& m, const Vertex& v) {
  m.positions.push_back(glm::vec3(v.position));
  m.normals.push_back(glm::vec3(glm::normalize(v.normal)));
  m.uv0.push_back(glm::vec2(v.uv));
  return uint32_t(m.positions.size() - 1);
}

// A triangle with two coincident corners (a pole or a disc centre) adds nothing but a zero
// area the renderer would have to skip; generators snap such corners to equal values.
void addTriangle(Mesh& m, uint32_t a, uint32_t b, uint32_t c, bool flip) {
  const auto& p = m.positions;
  if (p[a] == p[b] || p[b] == p[c] || p[c] == p[a]) return;
  if (flip) std::swap(b, c);
  m.indices.insert(m.indices.end(), {a, b, c});
}

// A (ni + 1) x (nj + 1) vertex grid from f(i, j), two triangles per cell. The front face is
// along cross(dP/di, dP/dj) unless flip; every surface below is a parametric patch, so each
// generator only has to pick its parameter order once.
template <typename F>
void addGrid(Mesh& m, int ni, int nj, bool flip, F f) {
  const uint32_t base = uint32_t(m.positions.size());
  for (int i = 0; i <= ni; ++i)
    for (int j = 0; j <= nj; ++j) addVertex(m, f(i, j));
  const auto at = [&](int i, int j) { return base + uint32_t(i * (nj + 1) + j); };
  for (int i = 0; i < ni; ++i)
    for (int j = 0; j < nj; ++j) {
      addTriangle(m, at(i, j), at(i + 1, j), at(i, j + 1), flip);
      addTriangle(m, at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), flip);
    }
}

// A disc of radius r at height y facing +Y (or -Y when down), fanned from its centre.
void addDisc(Mesh& m, double r, double y, int segments, bool down) {
  addGrid(m, 1, segments, down, [&](int i, int j) {
    const double phi = 2.0 * kPi * j / segments;
    const glm::dvec2 d(std::sin(phi), std::cos(phi));
    const double rho = r * i;  // i = 0 is the centre, shared exactly by every spoke
    return Vertex{{rho * d.x, y, rho * d.y},
                  {0.0, down ? -1.0 : 1.0, 0.0},
                  {0.5 + 0.5 * i * d.x, 0.5 - 0.5 * i * d.y}};
  });
}

template <typename T>
void appendAttribute(std::vector<T>& dst, const std::vector<T>& src, size_t dstVertices) {
  if (dst.size() == dstVertices && !src.empty())
    dst.insert(dst.end(), src.begin(), src.end());
  else
    dst.clear();
}

}  // namespace

Mesh makeQuad(const glm::vec3& origin, const glm::vec3& edgeU, const glm::vec3& edgeV) {
  Mesh m;
  m.name = "quad";
  const glm::dvec3 o(origin), u(edgeU), v(edgeV);
  const glm::dvec3 n = glm::cross(u, v);
  addGrid(m, 1, 1, false, [&](int i, int j) {
    return Vertex{o + double(i) * u + double(j) * v, n, {double(i), 1.0 - j}};
  });
  return m;
}

Mesh makeBox(const glm::vec3& min, const glm::vec3& max) {
  const glm::vec3 d = max - min;
  const glm::vec3 x(d.x, 0, 0), y(0, d.y, 0), z(0, 0, d.z);
  // (origin, edgeU, edgeV) per face with cross(edgeU, edgeV) pointing out of the box.
  const glm::vec3 faces[6][3] = {
      {{max.x, min.y, max.z}, -z, y}, {min, z, y},
      {{min.x, min.y, max.z}, x, y},  {{max.x, min.y, min.z}, -x, y},
      {{min.x, max.y, max.z}, x, -z}, {min, x, z},
  };
  Mesh box;
  for (const auto& f : faces) appendMesh(box, makeQuad(f[0], f[1], f[2]));
  box.name = "box";
  return box;
}

Mesh makeUvSphere(float radius, int segments, int rings) {
  assert(segments >= 3 && rings >= 2);
  Mesh m;
  m.name = "sphere";
  // i walks from the north pole south, j eastwards: cross(dP/di, dP/dj) points outwards.
  addGrid(m, rings, segments, false, [&](int i, int j) {
    const double theta = kPi * i / rings, phi = 2.0 * kPi * j / segments;
    const bool pole = i == 0 || i == rings;  // exact, so pole triangles are detected
    const double s = pole ? 0.0 : std::sin(theta);
    const double c = i == 0 ? 1.0 : (i == rings ? -1.0 : std::cos(theta));
    const glm::dvec3 n(s * std::sin(phi), c, s * std::cos(phi));
    return Vertex{double(radius) * n, n, {double(j) / segments, double(i) / rings}};
  });
  return m;
}

Mesh makeCylinder(float radius, float height, int segments, int rings, bool capped) {
  assert(segments >= 3 && rings >= 1);
  Mesh m;
  m.name = "cylinder";
  // i walks down from the top, j around: cross(dP/di, dP/dj) points outwards.
  addGrid(m, rings, segments, false, [&](int i, int j) {
    const double phi = 2.0 * kPi * j / segments;
    const glm::dvec3 n(std::sin(phi), 0.0, std::cos(phi));
    const double y = double(height) * (1.0 - double(i) / rings);
    return Vertex{{radius * n.x, y, radius * n.z}, n, {double(j) / segments, double(i) / rings}};
  });
  if (capped) {
    addDisc(m, radius, height, segments, false);
    addDisc(m, radius, 0.0, segments, true);
  }
  return m;
}

Mesh makeArch(float innerRadius, float thickness, float depth, int segments) {
  assert(segments >= 1 && thickness > 0.0f && depth > 0.0f);
  Mesh m;
  m.name = "arch";
  const double r0 = innerRadius, r1 = double(innerRadius) + thickness, hd = 0.5 * depth;
  const auto dir = [&](int j) {
    const double a = kPi * j / segments;
    return glm::dvec3(std::cos(a), std::sin(a), 0.0);
  };
  // Extrados (outward) and intrados (towards the centre): i around the arch, j along depth.
  for (const bool inner : {false, true})
    addGrid(m, segments, 1, inner, [&](int i, int j) {
      const glm::dvec3 d = dir(i);
      const double r = inner ? r0 : r1;
      return Vertex{r * d + glm::dvec3(0, 0, -hd + depth * j),
                    inner ? -d : d,
                    {double(i) / segments, double(j)}};
    });
  // Front and back: i from intrados to extrados, j around; cross points along +Z.
  for (const bool back : {false, true})
    addGrid(m, 1, segments, back, [&](int i, int j) {
      const glm::dvec3 p = (i == 0 ? r0 : r1) * dir(j) + glm::dvec3(0, 0, back ? -hd : hd);
      return Vertex{p, {0, 0, back ? -1 : 1}, {0.5 + 0.5 * p.x / r1, 1.0 - p.y / r1}};
    });
  const glm::vec3 across(thickness, 0, 0), along(0, 0, depth);
  appendMesh(m, makeQuad({innerRadius, 0, -hd}, across, along));  // feet face -Y
  appendMesh(m, makeQuad({-float(r1), 0, -hd}, across, along));
  return m;
}

void transformMesh(Mesh& mesh, const glm::mat4& transform) {
  const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(transform));
  for (glm::vec3& p : mesh.positions) p = glm::vec3(transform * glm::vec4(p, 1.0f));
  for (glm::vec3& n : mesh.normals) n = glm::normalize(normalMatrix * n);
  for (glm::vec4& t : mesh.tangents)
    t = glm::vec4(glm::normalize(glm::mat3(transform) * glm::vec3(t)), t.w);
  if (glm::determinant(glm::mat3(transform)) < 0.0f) {
    for (size_t t = 0; t < mesh.triangleCount(); ++t)
      std::swap(mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]);
    for (glm::vec4& t : mesh.tangents) t.w = -t.w;  // a mirror flips the bitangent
  }
}

void appendMesh(Mesh& dst, const Mesh& src) {
  if (dst.positions.empty()) {
    const std::string name = dst.name;
    const int material = dst.material;
    dst = src;
    dst.name = name.empty() ? src.name : name;
    dst.material = material;
    return;
  }
  const size_t n = dst.positions.size();
  appendAttribute(dst.normals, src.normals, n);
  appendAttribute(dst.tangents, src.tangents, n);
  appendAttribute(dst.uv0, src.uv0, n);
  appendAttribute(dst.uv1, src.uv1, n);
  dst.positions.insert(dst.positions.end(), src.positions.begin(), src.positions.end());
  for (uint32_t i : src.indices) dst.indices.push_back(uint32_t(n) + i);
}

void flipMesh(Mesh& mesh) {
  for (size_t t = 0; t < mesh.triangleCount(); ++t)
    std::swap(mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]);
  for (glm::vec3& n : mesh.normals) n = -n;
  for (glm::vec4& t : mesh.tangents) t.w = -t.w;
}

double meshSurfaceArea(const Mesh& mesh) {
  double area = 0.0;
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]);
    const glm::dvec3 b(mesh.positions[mesh.indices[3 * t + 1]]);
    const glm::dvec3 c(mesh.positions[mesh.indices[3 * t + 2]]);
    area += 0.5 * glm::length(glm::cross(b - a, c - a));
  }
  return area;
}

double meshSignedVolume(const Mesh& mesh) {
  double volume = 0.0;
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]);
    const glm::dvec3 b(mesh.positions[mesh.indices[3 * t + 1]]);
    const glm::dvec3 c(mesh.positions[mesh.indices[3 * t + 2]]);
    volume += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return volume;
}

}  // namespace photovr
