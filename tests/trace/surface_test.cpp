#include "trace/surface.h"

#include <gtest/gtest.h>

#include "tests/trace/trace_test_util.h"

namespace photovr {
namespace {

using testing::addSquare;
using testing::diffuseMaterial;

// The path tracer rebuilds a path's last hit with surfaceEmissionAt; its emission and MIS
// weight (position, geometric normal) must be surfaceAt's to the bit, or the image changes.
TEST(SurfaceEmissionAt, EqualsSurfaceAtInWhatItFills) {
  Scene s;
  Texture t;  // an emissive texture with a gradient, so uv interpolation matters
  t.name = "gradient";
  t.width = 2;
  t.height = 2;
  t.rgba = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 40, 80, 120, 255};
  s.textures.push_back(t);
  for (bool doubleSided : {false, true}) {
    for (bool textured : {false, true}) {
      Material m = diffuseMaterial(glm::vec3(0.3f, 0.5f, 0.7f));
      m.emissiveFactor = glm::vec3(2.0f, 1.0f, 0.5f);
      m.doubleSided = doubleSided;
      if (textured) m.emissiveTexture.texture = 0;
      s.materials.push_back(m);
    }
  }
  // Far from the origin, rotated and scaled, so every float operation has rounding to match.
  const glm::mat4 transform =
      glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), {103.7f, -2.1f, 55.3f}), 0.7f,
                             glm::normalize(glm::vec3(1, 2, 3))),
                 glm::vec3(1.7f, 0.6f, 2.3f));
  for (int material = 0; material < int(s.materials.size()); ++material)
    addSquare(s, 1.3f, material, transform);
  const glm::vec3 normal = glm::normalize(glm::vec3(glm::transpose(glm::inverse(transform))[2]));
  for (uint32_t instance = 0; instance < s.instances.size(); ++instance) {
    for (uint32_t triangle = 0; triangle < 2; ++triangle) {
      for (float side : {-1.0f, 1.0f}) {  // front and back hits
        const glm::vec3 incoming = glm::normalize(side * normal + glm::vec3(0.1f, -0.2f, 0.05f));
        for (int k = 0; k < 16; ++k) {
          const float b1 = 0.05f + 0.057f * float(k), b2 = 0.9f - b1 - 0.01f * float(k % 3);
          const SurfaceHit a = surfaceAt(s, instance, triangle, b1, b2, incoming);
          const SurfaceHit e = surfaceEmissionAt(s, instance, triangle, b1, b2, incoming);
          ASSERT_EQ(a.position, e.position);
          ASSERT_EQ(a.positionError, e.positionError);
          ASSERT_EQ(a.geometricNormal, e.geometricNormal);
          ASSERT_EQ(a.frontFace, e.frontFace);
          ASSERT_EQ(a.emission, e.emission) << instance << " " << side;
          ASSERT_EQ(a.instance, e.instance);
          ASSERT_EQ(a.triangle, e.triangle);
        }
      }
    }
  }
}

}  // namespace
}  // namespace photovr
