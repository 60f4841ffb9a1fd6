#include "bench/sampler_scenes.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include <glm/gtc/matrix_transform.hpp>

#include "core/camera.h"
#include "core/environment_io.h"
#include "core/error.h"
#include "core/gltf_loader.h"
#include "core/gltf_writer.h"
#include "core/image_io.h"
#include "core/mesh_gen.h"

namespace photovr::bench {
namespace {

constexpr float kPi = 3.14159265f;

// --- Panoramas ---------------------------------------------------------------------------

using Radiance = std::function<glm::vec3(const glm::vec3& direction)>;

// Equirectangular as photovr reads it (trace/environment_sampling.cpp): u = 0.5 +
// atan2(z, x) / 2pi, v = 0.5 + elevation / pi with v = 1 on the top row.
ImageF panorama(int width, const Radiance& radiance) {
  const int height = width / 2;
  ImageF img(width, height, 3);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const float phi = 2 * kPi * ((i + 0.5f) / width - 0.5f);
      const float elevation = kPi * (0.5f - (j + 0.5f) / height);
      const glm::vec3 d(std::cos(elevation) * std::cos(phi), std::sin(elevation),
                        std::cos(elevation) * std::sin(phi));
      const glm::vec3 l = radiance(d);
      std::copy(&l.x, &l.x + 3, img.at(i, j));
    }
  return img;
}

// Inside a cone of half-angle 'radius' around 'axis', with a smooth rim of 20 % of it.
float disc(const glm::vec3& d, const glm::vec3& axis, float radius) {
  const float angle = std::acos(std::clamp(glm::dot(d, glm::normalize(axis)), -1.0f, 1.0f));
  return std::clamp((radius - angle) / (0.2f * radius), 0.0f, 1.0f);
}

// A clear day: gradient sky, darker ground, and a 2.5-degree sun of radiance 300 (its
// irradiance, ~0.006 sr x 300 = 1.7, about that of the sky, pi x ~0.5): a bright, small
// source that the environment's importance sampling must find, as in a real outdoor HDR.
glm::vec3 outdoor(const glm::vec3& d) {
  const glm::vec3 sky = glm::mix(glm::vec3(0.75f, 0.8f, 0.9f), glm::vec3(0.2f, 0.35f, 0.75f),
                                 std::sqrt(std::max(d.y, 0.0f)));
  const glm::vec3 ground(0.18f, 0.16f, 0.14f);
  const float sun = disc(d, {0.5f, 0.6f, 0.62f}, glm::radians(2.5f));
  return (d.y >= 0 ? sky : ground) + sun * glm::vec3(300.0f, 285.0f, 260.0f);
}

// A photo studio: a dim surround, two large soft boxes (radiance 12 and 6, ~25 degrees
// across) and a narrow strip light overhead behind the set: sources of several sizes.
glm::vec3 studio(const glm::vec3& d) {
  const glm::vec3 surround = glm::vec3(0.03f) + 0.03f * std::max(d.y, 0.0f);
  const float key = disc(d, {-0.7f, 0.5f, 0.5f}, glm::radians(13.0f));
  const float fill = disc(d, {0.8f, 0.2f, 0.55f}, glm::radians(12.0f));
  const float strip = std::abs(d.x) < 0.06f && d.y > 0.55f && d.z < 0.0f ? 1.0f : 0.0f;
  return surround + key * glm::vec3(12.0f, 11.5f, 10.5f) + fill * glm::vec3(6.0f) +
         strip * glm::vec3(20.0f);
}

// --- Scene assembly ----------------------------------------------------------------------

Material material(const std::string& name, const glm::vec3& color, float metallic,
                  float roughness) {
  Material m;
  m.name = name;
  m.baseColorFactor = glm::vec4(color, 1.0f);
  m.metallicFactor = metallic;
  m.roughnessFactor = roughness;
  return m;
}

void add(Scene& scene, Mesh mesh, const Material& m, const glm::mat4& transform) {
  scene.materials.push_back(m);
  mesh.name = m.name;
  mesh.material = int(scene.materials.size() - 1);
  scene.meshes.push_back(std::move(mesh));
  Instance inst;
  inst.mesh = int(scene.meshes.size() - 1);
  inst.transform = inst.previousTransform = transform;
  inst.node = m.name;
  scene.instances.push_back(inst);
}

Camera camera(const std::string& name, const glm::vec3& eye, const glm::vec3& target,
              float yfovDegrees) {
  const Pose pose = lookAt(eye, target);
  return {name, pose.position, pose.orientation, glm::radians(yfovDegrees)};
}

glm::mat4 at(const glm::vec3& t) {
  return glm::translate(glm::mat4(1.0f), t);
}

Mesh floorQuad(float half) {
  return makeQuad({-half, 0, half}, {2 * half, 0, 0}, {0, 0, -2 * half});
}

Scene metalScene() {
  Scene s;
  s.name = "metal-gltf";
  add(s, floorQuad(4.0f), material("floor", glm::vec3(0.45f), 0.0f, 0.6f), glm::mat4(1.0f));
  const glm::vec3 colors[5] = {{1.0f, 0.78f, 0.34f},    // gold
                               {0.95f, 0.64f, 0.54f},   // copper
                               {0.97f, 0.96f, 0.91f},   // silver
                               {0.91f, 0.92f, 0.92f},   // aluminium
                               {0.56f, 0.57f, 0.58f}};  // iron
  const float roughness[5] = {0.05f, 0.2f, 0.35f, 0.5f, 0.8f};
  for (int i = 0; i < 5; ++i)
    add(s, makeUvSphere(0.3f, 48, 24),
        material("metal-" + std::to_string(i), colors[i], 1.0f, roughness[i]),
        at({0.7f * (i - 2), 0.3f, 0.0f}));
  add(s, makeArch(0.9f, 0.18f, 0.3f, 48), material("arch", glm::vec3(0.9f), 1.0f, 0.3f),
      at({0.0f, 0.0f, -0.9f}));
  s.cameras.push_back(camera("metal-view", {0.0f, 0.9f, 3.0f}, {0.0f, 0.45f, 0.0f}, 40.0f));
  return s;
}

Texture texture(const std::string& name, int size,
                const std::function<glm::vec3(float u, float v)>& srgb) {
  Texture t;
  t.name = name;
  t.width = t.height = size;
  t.rgba.resize(size_t(size) * size * 4);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const glm::vec3 c = srgb((x + 0.5f) / size, (y + 0.5f) / size);
      uint8_t* p = &t.rgba[4 * (size_t(y) * size + x)];
      for (int k = 0; k < 3; ++k) p[k] = uint8_t(std::clamp(c[k], 0.0f, 1.0f) * 255.0f + 0.5f);
      p[3] = 255;
    }
  return t;
}

Material textured(Scene& s, const std::string& name, Texture t, float roughness) {
  s.textures.push_back(std::move(t));
  Material m = material(name, glm::vec3(1.0f), 0.0f, roughness);
  m.baseColorTexture.texture = int(s.textures.size() - 1);
  return m;
}

Scene texturedScene() {
  Scene s;
  s.name = "textured-gltf";
  const auto checker = [](float u, float v) {
    return (int(u * 8) + int(v * 8)) % 2 ? glm::vec3(0.85f, 0.82f, 0.75f)
                                         : glm::vec3(0.2f, 0.22f, 0.25f);
  };
  const auto bricks = [](float u, float v) {
    const float row = v * 6, shift = int(row) % 2 ? 0.5f : 0.0f;
    const bool mortar = row - int(row) < 0.1f || std::fmod(u * 3 + shift, 1.0f) < 0.05f;
    return mortar ? glm::vec3(0.75f) : glm::vec3(0.62f, 0.25f, 0.16f);
  };
  const auto stripes = [](float u, float) {
    return int(u * 12) % 2 ? glm::vec3(0.1f, 0.3f, 0.65f) : glm::vec3(0.9f, 0.85f, 0.3f);
  };
  add(s, floorQuad(3.0f), textured(s, "checker-floor", texture("checker", 256, checker), 0.7f),
      glm::mat4(1.0f));
  add(s, makeBox({-0.35f, 0, -0.35f}, {0.35f, 0.7f, 0.35f}),
      textured(s, "brick-box", texture("bricks", 256, bricks), 0.85f),
      glm::rotate(at({-0.8f, 0, -0.2f}), 0.5f, glm::vec3(0, 1, 0)));
  add(s, makeCylinder(0.25f, 0.9f, 48, 1, true),
      textured(s, "striped-cylinder", texture("stripes", 128, stripes), 0.4f),
      at({0.75f, 0, -0.4f}));
  add(s, makeUvSphere(0.28f, 48, 24), material("glossy-red", {0.7f, 0.08f, 0.06f}, 0.0f, 0.15f),
      at({0.1f, 0.28f, 0.45f}));
  s.cameras.push_back(camera("textured-view", {0.3f, 1.3f, 2.8f}, {0.0f, 0.3f, 0.0f}, 45.0f));
  return s;
}

}  // namespace

std::vector<std::string> gltfSceneNames() {
  return {"metal-gltf", "textured-gltf"};
}

bool isGltfScene(const std::string& name) {
  const std::vector<std::string> names = gltfSceneNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

Scene makeGltfScene(const std::string& name, const std::string& dir) {
  if (!isGltfScene(name)) throw UsageError("unknown glTF bench scene '" + name + "'");
  const bool metal = name == "metal-gltf";
  const std::string glb = dir + "/" + name + ".glb", hdr = dir + "/" + name + ".hdr";
  writeGlb(metal ? metalScene() : texturedScene(), glb);
  writeImage(hdr, panorama(1024, metal ? Radiance(outdoor) : Radiance(studio)));
  Scene scene = loadGltf(glb);
  scene.environment = loadEnvironment(hdr);
  return scene;
}

}  // namespace photovr::bench
