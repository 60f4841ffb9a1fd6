// The scenes of the glTF material-extension study against Blender Cycles (issue 22,
// bench/materials_vs_cycles.sh): the built-in Cornell box with one material changed per
// scene, written as .gltf by photovr's own writer so that both renderers read the same
// file. Usage: photovr_material_study DIR  (writes DIR/<name>.gltf, prints the names).
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/builtin_scenes.h"
#include "core/error.h"
#include "core/gltf_writer.h"
#include "core/mesh_gen.h"

namespace photovr {
namespace {

Material& materialNamed(Scene& s, const std::string& name) {
  for (Material& m : s.materials)
    if (m.name == name) return m;
  throw InputError("cornell", "no material " + name);
}

// Every non-emissive dielectric as KHR_materials_specular 0 / KHR_materials_ior 1: the
// "pure diffuse walls" of a real Cornell-box asset (issue 22).
void pureDiffuse(Scene& s) {
  for (Material& m : s.materials)
    if (!m.isEmissive() && m.metallicFactor == 0.0f) {
      m.specularFactor = 0.0f;
      m.ior = 1.0f;
    }
}

void iorAndTint(Scene& s) {
  Material& m = materialNamed(s, "cornell-rough");
  m.roughnessFactor = 0.2f;
  m.ior = 2.4f;
  m.specularColorFactor = glm::vec3(1.0f, 0.6f, 0.3f);
}

// The short block replaced by a glass sphere of radius 0.3 m resting on the floor.
void glassSphere(Scene& s, float roughness, bool volume, glm::vec3 attenuation) {
  Material g;
  g.name = "glass";
  g.baseColorFactor = glm::vec4(1.0f);
  g.metallicFactor = 0.0f;
  g.roughnessFactor = roughness;
  g.transmissionFactor = 1.0f;
  g.thicknessFactor = volume ? 0.6f : 0.0f;
  g.attenuationColor = attenuation;
  g.attenuationDistance = attenuation == glm::vec3(1.0f) ? 0.0f : 0.5f;
  s.materials.push_back(g);
  Mesh sphere = makeUvSphere(0.3f, 128, 64);
  sphere.name = "glass-sphere";
  sphere.material = int(s.materials.size() - 1);
  for (Instance& inst : s.instances)
    if (inst.node == "short-block") {
      s.meshes.push_back(sphere);
      inst.mesh = int(s.meshes.size() - 1);
      inst.transform = inst.previousTransform =
          glm::translate(glm::mat4(1.0f), glm::vec3(0.38f, 0.3f, 0.3f));
    }
}

// Every non-emissive dielectric under a clear coat (KHR_materials_clearcoat) or with a
// sheen (KHR_materials_sheen).
void clearcoat(Scene& s) {
  for (Material& m : s.materials)
    if (!m.isEmissive() && m.metallicFactor == 0.0f) {
      m.clearcoatFactor = 1.0f;
      m.clearcoatRoughnessFactor = 0.1f;
    }
}

void sheen(Scene& s) {
  for (Material& m : s.materials)
    if (!m.isEmissive() && m.metallicFactor == 0.0f) {
      m.sheenColorFactor = glm::vec3(1.0f);
      m.sheenRoughnessFactor = 0.5f;
    }
}

struct Variant {
  std::string name;
  std::function<void(Scene&)> change;
};

const std::vector<Variant>& variants() {
  static const std::vector<Variant> v = {
      {"cornell-core", [](Scene&) {}},
      {"cornell-specular0", pureDiffuse},
      {"cornell-ior", iorAndTint},
      {"cornell-glass",
       [](Scene& s) {
         glassSphere(s, 0.0f, true, {0.9f, 0.6f, 0.3f});
       }},
      {"cornell-rough-glass", [](Scene& s) { glassSphere(s, 0.3f, true, glm::vec3(1.0f)); }},
      {"cornell-thin-glass", [](Scene& s) { glassSphere(s, 0.0f, false, glm::vec3(1.0f)); }},
      // The walls where the two renderers' models coincide (pure diffuse), with glass.
      {"cornell-specular0-glass",
       [](Scene& s) {
         pureDiffuse(s);
         glassSphere(s, 0.0f, true, {0.9f, 0.6f, 0.3f});
       }},
      {"cornell-clearcoat", clearcoat},
      {"cornell-specular0-clearcoat",
       [](Scene& s) {
         pureDiffuse(s);
         clearcoat(s);
       }},
      {"cornell-sheen", sheen},
      {"cornell-specular0-sheen", [](Scene& s) {
         pureDiffuse(s);
         sheen(s);
       }}};
  return v;
}

}  // namespace
}  // namespace photovr

int main(int argc, char** argv) {
  using namespace photovr;
  if (argc != 2) {
    std::fprintf(stderr, "usage: photovr_material_study DIR\n");
    return 2;
  }
  try {
    std::filesystem::create_directories(argv[1]);
    for (const Variant& v : variants()) {
      Scene s = makeBuiltinScene("cornell");
      v.change(s);
      s.name = v.name;
      writeGlb(s, std::string(argv[1]) + "/" + v.name + ".gltf");
      std::printf("%s\n", v.name.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "photovr_material_study: %s\n", e.what());
    return 1;
  }
  return 0;
}
