#include "tests/gl/gl_test_util.h"

namespace photovr::testing {

gl::Context& osmesaContext() {
  static std::unique_ptr<gl::Context> context = gl::Context::create({gl::Backend::OSMesa});
  context->makeCurrent();
  return *context;
}

Mesh rectangleMesh(float hx, float hy, int material) {
  Mesh m;
  m.name = "rectangle";
  m.positions = {{-hx, -hy, 0}, {hx, -hy, 0}, {hx, hy, 0}, {-hx, hy, 0}};
  m.normals.assign(4, glm::vec3(0, 0, 1));
  m.uv0 = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.material = material;
  return m;
}

Material plainMaterial(glm::vec3 baseColor, float metallic, float roughness) {
  Material m;
  m.baseColorFactor = glm::vec4(baseColor, 1.0f);
  m.metallicFactor = metallic;
  m.roughnessFactor = roughness;
  return m;
}

}  // namespace photovr::testing
