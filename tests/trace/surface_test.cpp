#include "trace/surface.h"

#include <gtest/gtest.h>

#include "tests/trace/surface_bits.h"
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

// KHR_materials_clearcoat's normal: the coat's own map on the interpolated normal, never
// the base's map (glTF: "If clearcoatNormalTexture is not given, no normal mapping is
// applied to the clear coat layer"), handed to the BSDF in the base's shading frame.
TEST(SurfaceAt, TheCoatTakesItsOwnNormalMapNotTheBases) {
  // A 1 x 1 normal map tilting the normal 30 degrees towards +x: (sin 30, 0, cos 30) as
  // linear bytes (n + 1) / 2 * 255.
  Scene s;
  Texture t;
  t.name = "tilt";
  t.width = t.height = 1;
  t.rgba = {191, 128, 238, 255};
  s.textures.push_back(t);
  const glm::vec3 decoded =
      glm::normalize(glm::vec3(191.0f, 128.0f, 238.0f) / 255.0f * 2.0f - 1.0f);
  struct Case {
    bool baseMap, coatMap;
    glm::vec3 shading, coat;  // the expected world normals
  };
  const glm::vec3 up(0, 0, 1);
  for (const Case& c : {Case{false, false, up, up}, Case{true, false, decoded, up},
                        Case{false, true, up, decoded}, Case{true, true, decoded, decoded}}) {
    Scene scene = s;
    Material m = diffuseMaterial(glm::vec3(0.5f));
    m.clearcoatFactor = 1.0f;
    if (c.baseMap) m.normalTexture.texture = 0;
    if (c.coatMap) m.clearcoatNormalTexture.texture = 0;
    scene.materials.push_back(m);
    addSquare(scene, 1.0f, 0, glm::mat4(1.0f));
    scene.meshes[0].tangents.assign(4, glm::vec4(1, 0, 0, 1));
    const SurfaceHit h = surfaceAt(scene, 0, 0, 0.3f, 0.3f, glm::vec3(0, 0, -1));
    SCOPED_TRACE(::testing::Message() << "base map " << c.baseMap << " coat map " << c.coatMap);
    // 1e-5: float rounding of the decode, the normalisations and the frame.
    EXPECT_LT(glm::length(h.shadingNormal - c.shading), 1e-5f);
    const glm::vec3 coatWorld = Frame::fromZ(h.shadingNormal).toWorld(h.bsdf.coatNormal);
    EXPECT_LT(glm::length(coatWorld - c.coat), 1e-5f);
    // The same normal for both: exactly +z in the shading frame, the untilted coat.
    if (c.baseMap == c.coatMap) {
      EXPECT_EQ(h.bsdf.coatNormal, up);
    }
  }
}

// The tracer takes an untextured material's inputs from a table built once per scene
// (MaterialTable); they must be what surfaceAt computes at the hit, to the bit, on both
// sides, for every kind of material (or the images change), and a textured material must
// still be computed at the hit.
TEST(MaterialTable, GivesSurfaceAtsInputsBitForBit) {
  Scene s;
  Texture t;  // a base colour gradient: the textured material varies over the square
  t.name = "gradient";
  t.width = t.height = 2;
  t.rgba = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 40, 80, 120, 255};
  s.textures.push_back(t);
  std::vector<Material> kinds(10, diffuseMaterial(glm::vec3(0.3f, 0.5f, 0.7f)));
  kinds[1].metallicFactor = 0.8f, kinds[1].roughnessFactor = 0.35f;
  kinds[2].ior = 1.33f, kinds[2].specularFactor = 0.6f,
  kinds[2].specularColorFactor = {1, .5f, .2f};
  kinds[3].transmissionFactor = 1.0f, kinds[3].thicknessFactor = 0.1f, kinds[3].ior = 1.45f;
  kinds[4].sheenColorFactor = {0.9f, 0.2f, 0.4f}, kinds[4].sheenRoughnessFactor = 0.5f;
  kinds[5].clearcoatFactor = 0.7f, kinds[5].clearcoatRoughnessFactor = 0.1f;
  kinds[6].unlit = true;
  kinds[7].emissiveFactor = {2.0f, 1.0f, 0.5f}, kinds[7].emissiveStrength = 3.0f;
  kinds[8] = kinds[7], kinds[8].doubleSided = true;
  kinds[9].baseColorTexture.texture = 0;
  s.materials = kinds;
  const glm::mat4 transform =  // far away, rotated and scaled: every operation rounds
      glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), {-803.7f, 12.1f, 55.3f}), 0.7f,
                             glm::normalize(glm::vec3(1, 2, 3))),
                 glm::vec3(1.7f, 0.6f, 2.3f));
  for (int material = 0; material < int(s.materials.size()); ++material)
    addSquare(s, 1.3f, material, transform);
  const MaterialTable table(s);
  for (size_t m = 0; m < s.materials.size(); ++m)
    EXPECT_EQ(table.constantOf(m) == nullptr, m == 9) << m;
  const glm::vec3 normal = glm::normalize(glm::vec3(glm::transpose(glm::inverse(transform))[2]));
  for (uint32_t instance = 0; instance < s.instances.size(); ++instance)
    for (float side : {-1.0f, 1.0f}) {  // front and back hits
      SCOPED_TRACE(::testing::Message() << "material " << instance << " side " << side);
      const glm::vec3 incoming = glm::normalize(side * normal + glm::vec3(0.1f, -0.2f, 0.05f));
      for (int k = 0; k < 8; ++k) {
        const HitRef ref{instance, uint32_t(k % 2), 0.05f + 0.1f * float(k), 0.4f};
        const HitGeometry g = hitGeometry(s, ref);
        testing::expectSameBits(surfaceAt(s, table, ref, g, incoming),
                                surfaceAt(s, ref, g, incoming));
      }
    }
}

}  // namespace
}  // namespace photovr
