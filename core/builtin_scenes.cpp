#include "core/builtin_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "core/mesh_gen.h"

namespace photovr {
namespace {

constexpr float kPi = 3.14159265f;

// ---------------------------------------------------------------------------------------
// Scene assembly helpers

Material dielectric(const std::string& name, const glm::vec3& color, float roughness) {
  Material m;
  m.name = name;
  m.baseColorFactor = glm::vec4(color, 1.0f);
  m.metallicFactor = 0.0f;
  m.roughnessFactor = roughness;
  return m;
}

Material metal(const std::string& name, const glm::vec3& color, float roughness) {
  Material m = dielectric(name, color, roughness);
  m.metallicFactor = 1.0f;
  return m;
}

int addMaterial(Scene& scene, const Material& material) {
  scene.materials.push_back(material);
  return int(scene.materials.size() - 1);
}

int addMesh(Scene& scene, Mesh mesh, const std::string& name, int material) {
  mesh.name = name;
  mesh.material = material;
  scene.meshes.push_back(std::move(mesh));
  return int(scene.meshes.size() - 1);
}

void addInstance(Scene& scene, int mesh, const glm::mat4& transform, const std::string& node) {
  Instance inst;
  inst.mesh = mesh;
  inst.transform = transform;
  inst.previousTransform = transform;  // static scenes: no motion
  inst.node = node;
  scene.instances.push_back(inst);
}

// A mesh used once, already in world space.
void addStatic(Scene& scene, Mesh mesh, const std::string& name, int material) {
  addInstance(scene, addMesh(scene, std::move(mesh), name, material), glm::mat4(1.0f), name);
}

Camera lookAtCamera(const std::string& name, const glm::vec3& eye, const glm::vec3& target,
                    float yfovDegrees) {
  Camera c;
  c.name = name;
  c.position = eye;
  // quatLookAtRH maps the camera's -Z onto the direction with +Y kept up (glTF camera).
  c.orientation = glm::quatLookAtRH(glm::normalize(target - eye), glm::vec3(0, 1, 0));
  c.yfov = glm::radians(yfovDegrees);
  return c;
}

glm::mat4 translateRotateY(const glm::vec3& t, float degrees) {
  return glm::rotate(glm::translate(glm::mat4(1.0f), t), glm::radians(degrees), glm::vec3(0, 1, 0));
}

// A clear-day gradient sky shared by the open scenes. Values are linear radiance chosen for
// an exposure of 1: zenith (luminance ~0.2) and horizon (~0.45) stay below a sunlit white
// surface (~1.0, see kSunLux), as the sky is below a sunlit wall in a photograph, and the
// sky's irradiance on the ground (~pi * 0.3 = 0.9) is about a quarter of the sun's (4 on
// the ground), inside the 1:3 .. 1:10 diffuse-to-direct range of a clear day.
Environment clearSky() {
  Environment env;
  env.type = Environment::Type::Sky;
  env.name = "builtin-sky";
  env.sunDirection = glm::normalize(glm::vec3(0.45f, 0.8f, 0.4f));  // ~53 deg elevation
  env.zenithColor = glm::vec3(0.12f, 0.22f, 0.45f);
  env.horizonColor = glm::vec3(0.4f, 0.45f, 0.5f);
  env.groundColor = glm::vec3(0.12f, 0.11f, 0.1f);
  env.intensity = 1.0f;
  return env;
}

// Illuminance of the sun (scene units; the renderer treats lux as radiance * sr). A white
// Lambert surface (albedo 0.8) facing a 53-degree sun reflects 0.8 * 5 * 0.8 / pi = 1.0,
// the top of the exposure-1 range before the tone curve compresses it.
constexpr float kSunLux = 5.0f;

Light sunLight(const Environment& sky) {
  Light sun;
  sun.type = Light::Type::Directional;
  sun.name = "sun";
  sun.color = glm::vec3(1.0f, 0.95f, 0.88f);  // ~5800 K, slightly warm
  sun.intensity = kSunLux;
  sun.direction = -sky.sunDirection;  // the direction light travels
  return sun;
}

// ---------------------------------------------------------------------------------------
// cornell

// Classic Cornell box data (Cornell University Program of Computer Graphics): a 130 x 105 mm
// light in a 556 x 559 mm ceiling with radiance (17, 12, 4). Our light covers a larger
// fraction of the ceiling, so its radiance is scaled down to keep the same flux per wall
// area, and with it the brightness of the classic renders.
constexpr float kClassicLightFraction = (0.130f * 0.105f) / (0.556f * 0.559f);
constexpr float kCornellLightSize = 0.5f;  // a quarter of the 2 m ceiling's width
constexpr float kCornellLightFraction = (kCornellLightSize * kCornellLightSize) / 4.0f;

Material cornellLight() {
  Material m = dielectric("cornell-light", glm::vec3(0.78f), 1.0f);
  m.emissiveFactor = glm::vec3(1.0f, 12.0f / 17.0f, 4.0f / 17.0f);  // glTF keeps it in [0,1]
  m.emissiveStrength = 17.0f * kClassicLightFraction / kCornellLightFraction;
  return m;
}

// The six walls of x in [-1,1], y in [0,2], z in [-1,1], facing inwards. Corners are exact
// in float, so neighbouring walls share their edges bit for bit (no light leaks).
void addCornellWalls(Scene& scene) {
  const int white = addMaterial(scene, dielectric("cornell-white", glm::vec3(0.73f), 1.0f));
  const int red =
      addMaterial(scene, dielectric("cornell-red", glm::vec3(0.65f, 0.05f, 0.05f), 1.0f));
  const int green =
      addMaterial(scene, dielectric("cornell-green", glm::vec3(0.12f, 0.45f, 0.15f), 1.0f));
  Mesh whites = makeQuad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2});        // floor, +Y
  appendMesh(whites, makeQuad({-1, 2, -1}, {2, 0, 0}, {0, 0, 2}));  // ceiling, -Y
  appendMesh(whites, makeQuad({-1, 0, -1}, {2, 0, 0}, {0, 2, 0}));  // back, +Z
  appendMesh(whites, makeQuad({1, 0, 1}, {-2, 0, 0}, {0, 2, 0}));   // front, -Z
  addStatic(scene, std::move(whites), "cornell-white-walls", white);
  addStatic(scene, makeQuad({-1, 0, 1}, {0, 0, -2}, {0, 2, 0}), "cornell-left-wall", red);
  addStatic(scene, makeQuad({1, 0, -1}, {0, 0, 2}, {0, 2, 0}), "cornell-right-wall", green);
}

void addCornellBlocks(Scene& scene) {
  // Sizes and placement follow the classic blocks (165 mm and 330 mm tall in 556 mm),
  // scaled to the 2 m box and kept apart so that they never intersect.
  const int metalMat = addMaterial(scene, metal("cornell-metal", glm::vec3(0.95f, 0.93f, 0.88f),
                                                0.25f));  // silver-like F0
  const int roughMat = addMaterial(scene, dielectric("cornell-rough", glm::vec3(0.73f), 0.7f));
  const int tall = addMesh(scene, makeBox({-0.3f, 0, -0.3f}, {0.3f, 1.2f, 0.3f}),
                           "cornell-tall-block", metalMat);
  const int shortBlock = addMesh(scene, makeBox({-0.3f, 0, -0.3f}, {0.3f, 0.6f, 0.3f}),
                                 "cornell-short-block", roughMat);
  addInstance(scene, tall, translateRotateY({-0.4f, 0, -0.35f}, -18.0f), "tall-block");
  addInstance(scene, shortBlock, translateRotateY({0.38f, 0, 0.3f}, 17.0f), "short-block");
}

// The textured ceiling panel's emissive texture: kPanelTexels^2, lit in the central
// kPanelLit^2 texels from the centre.
constexpr int kPanelTexels = 64, kPanelLit = 4, kPanelCells = 32;

Texture panelTexture() {
  Texture t;
  t.name = "panel-emission";
  t.width = t.height = kPanelTexels;
  t.rgba.assign(size_t(kPanelTexels) * kPanelTexels * 4, 0);
  const int lo = kPanelTexels / 2;  // on a cell edge (2 texels per cell)
  for (int y = 0; y < kPanelTexels; ++y)
    for (int x = 0; x < kPanelTexels; ++x) {
      uint8_t* p = &t.rgba[(size_t(y) * kPanelTexels + x) * 4];
      const bool lit = x >= lo && x < lo + kPanelLit && y >= lo && y < lo + kPanelLit;
      p[0] = p[1] = p[2] = lit ? 255 : 0;
      p[3] = 255;
    }
  t.nearest = true;  // texel-sharp edges
  return t;
}

Scene makeCornell() {
  Scene scene;
  scene.name = "cornell";
  addCornellWalls(scene);
  addCornellBlocks(scene);
  const float h = 0.5f * kCornellLightSize;
  // 1 mm below the ceiling, facing down: cross(+X, +Z) = -Y.
  addStatic(scene, makeQuad({-h, 2.0f - 0.001f, -h}, {2 * h, 0, 0}, {0, 0, 2 * h}), "cornell-light",
            addMaterial(scene, cornellLight()));
  // Inside, 10 cm from the front wall; 55 degrees fits the 2 m back wall seen from 1.9 m.
  scene.cameras.push_back(lookAtCamera("cornell-view", {0, 1, 0.9f}, {0, 1, -1}, 55.0f));
  scene.environment.type = Environment::Type::None;
  return scene;
}

// ---------------------------------------------------------------------------------------
// spheres

constexpr int kSweep = 5;  // 0, .25, .5, .75, 1

Scene makeSpheres() {
  Scene scene;
  scene.name = "spheres";
  const Mesh sphere = makeUvSphere(0.4f, 64, 32);
  // Columns sweep perceptual roughness (x), rows metallic (y, dielectric at the bottom).
  for (int row = 0; row < kSweep; ++row)
    for (int col = 0; col < kSweep; ++col) {
      const float metallic = row / float(kSweep - 1), roughness = col / float(kSweep - 1);
      char name[64];
      std::snprintf(name, sizeof name, "sphere-metallic%.2f-roughness%.2f", metallic, roughness);
      Material m = dielectric(name, glm::vec3(0.9f, 0.5f, 0.3f), roughness);
      m.metallicFactor = metallic;
      // A mesh holds one material, so each sphere is its own mesh (same geometry).
      const int mesh = addMesh(scene, sphere, name, addMaterial(scene, m));
      addInstance(scene, mesh, glm::translate(glm::mat4(1.0f), {col - 2.0f, 0.6f + row, 0.0f}),
                  name);
    }
  const int ground = addMaterial(scene, dielectric("ground", glm::vec3(0.5f), 0.9f));
  // 200 m of ground: the sky's dark lower hemisphere stays below the horizon line.
  addStatic(scene, makeQuad({-100, 0, 100}, {200, 0, 0}, {0, 0, -200}), "ground", ground);
  scene.environment = clearSky();
  scene.lights.push_back(sunLight(scene.environment));
  // From 4.2 m the 5 x 4.8 m grid (centre y = 2.6) fills ~60 % of the DK2's 2.15-tangent
  // wide view; in mono, 62 degrees frames it (2 atan(2.4 / 4.2) = 59.5) with a margin.
  scene.cameras.push_back(lookAtCamera("spheres-view", {0, 2.6f, 4.2f}, {0, 2.5f, 0}, 62.0f));
  return scene;
}

// ---------------------------------------------------------------------------------------
// atrium: generated textures

uint32_t hash2(int x, int y) {  // integer hash (Wellons' lowbias32 on a packed key)
  uint32_t h = uint32_t(x) * 0x9E3779B1u ^ uint32_t(y) * 0x85EBCA77u;
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return h;
}

// Value noise with period `period` lattice cells, so the texture tiles under Repeat.
float periodicNoise(float x, float y, int period) {
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const float fx = x - x0, fy = y - y0;
  const auto v = [&](int i, int j) {
    const int px = ((x0 + i) % period + period) % period,
              py = ((y0 + j) % period + period) % period;
    return float(hash2(px, py) & 0xffffu) / 65535.0f;
  };
  const float sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
  return glm::mix(glm::mix(v(0, 0), v(1, 0), sx), glm::mix(v(0, 1), v(1, 1), sx), sy);
}

void setPixel(Texture& t, int x, int y, const glm::vec3& srgb, float alpha) {
  uint8_t* p = &t.rgba[4 * (size_t(y) * t.width + x)];
  for (int c = 0; c < 3; ++c) p[c] = uint8_t(std::clamp(srgb[c], 0.0f, 1.0f) * 255.0f + 0.5f);
  p[3] = uint8_t(std::clamp(alpha, 0.0f, 1.0f) * 255.0f + 0.5f);
}

Texture blankTexture(const std::string& name, int size) {
  Texture t;
  t.name = name;
  t.width = t.height = size;
  t.rgba.assign(size_t(size) * size * 4, 0);
  return t;
}

// 4 x 4 checker of light and dark marble with turbulent veins (sin of a noise-displaced
// diagonal, the classic Perlin marble); integer frequencies keep it tileable.
Texture marbleChecker() {
  constexpr int kSize = 256;
  Texture t = blankTexture("generated-marble-checker", kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const float u = x / float(kSize), v = y / float(kSize);
      const float turb = periodicNoise(u * 8, v * 8, 8) + 0.5f * periodicNoise(u * 16, v * 16, 16);
      const float vein = std::pow(0.5f + 0.5f * std::sin(2 * kPi * (3 * u + 2 * v) + 5 * turb), 6);
      const bool dark = ((x / 64) + (y / 64)) % 2 == 1;
      const glm::vec3 base = dark ? glm::vec3(0.36f, 0.33f, 0.31f) : glm::vec3(0.9f, 0.88f, 0.84f);
      setPixel(t, x, y, base * (0.92f + 0.08f * turb) - 0.25f * vein * base, 1.0f);
    }
  return t;
}

// Wooden lattice: square grid plus one diagonal per cell; alpha 0 in the holes (MASK).
Texture latticeAlpha() {
  constexpr int kSize = 128, kCell = 32, kBar = 3;
  Texture t = blankTexture("generated-lattice", kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const int cx = x % kCell, cy = y % kCell;
      const bool grid = cx < kBar || cx >= kCell - kBar || cy < kBar || cy >= kCell - kBar;
      const bool diagonal = std::abs(cx - cy) < kBar;
      setPixel(t, x, y, glm::vec3(0.45f, 0.3f, 0.18f), grid || diagonal ? 1.0f : 0.0f);
    }
  return t;
}

// ---------------------------------------------------------------------------------------
// atrium: layout (metres). Nave x in [-5, 5] between the colonnades, aisles out to the
// walls at |x| = 9, z in [-20, 20]; 10 column bays of 4 m; two storeys.

constexpr float kColumnX = 5.0f, kWallX = 9.0f, kHalfLength = 20.0f, kBay = 4.0f;
constexpr int kColumnsPerRow = 10;  // at z = -18, -14, ..., 18
constexpr float kShaftRadius = 0.3f, kPlinthRadius = 0.4f, kStageHeight = 0.25f;
constexpr float kSpringHeight = 4.0f;                     // top of the capital, where arches start
constexpr float kArchInner = 0.5f * kBay - kShaftRadius;  // springs from the shaft's face
constexpr float kArchThickness = kShaftRadius;  // neighbouring arches meet over the column
constexpr float kSlabThickness = 0.3f;
constexpr float kStoreyHeight = kSpringHeight + kArchInner + kArchThickness + kSlabThickness;
constexpr float kRoofLine = kStoreyHeight + kSpringHeight + kArchInner + kArchThickness + 0.5f;

struct AtriumMaterials {
  int stone, floor, bronze, lattice, plaster;
};

AtriumMaterials addAtriumMaterials(Scene& scene) {
  scene.textures.push_back(marbleChecker());
  scene.textures.push_back(latticeAlpha());
  AtriumMaterials m;
  m.stone = addMaterial(scene, dielectric("stone", glm::vec3(0.62f, 0.58f, 0.52f), 0.85f));
  Material floor = dielectric("polished-marble", glm::vec3(1.0f), 0.3f);
  floor.baseColorTexture.texture = 0;
  // One texture tile per 2 x 2 m (4 x 4 squares of 0.5 m) over the 18 x 40 m floor quad.
  floor.baseColorTexture.transform.scale = glm::vec2(2 * kWallX / 2.0f, 2 * kHalfLength / 2.0f);
  m.floor = addMaterial(scene, floor);
  // Bronze F0, roughly (0.80, 0.50, 0.28) as tabulated for polished bronze.
  m.bronze = addMaterial(scene, metal("bronze", glm::vec3(0.8f, 0.5f, 0.28f), 0.35f));
  Material lattice = dielectric("lattice-screen", glm::vec3(1.0f), 0.8f);
  lattice.baseColorTexture.texture = 1;
  lattice.baseColorTexture.transform.scale = glm::vec2(2.0f, 2.0f);
  lattice.alphaMode = AlphaMode::Mask;
  lattice.alphaCutoff = 0.5f;
  lattice.doubleSided = true;  // a screen is seen from both the nave and the aisle
  m.lattice = addMaterial(scene, lattice);
  m.plaster = addMaterial(scene, dielectric("plaster", glm::vec3(0.75f, 0.7f, 0.62f), 0.9f));
  return m;
}

float columnZ(int i) {
  return -kHalfLength + 0.5f * kBay + kBay * i;
}

// Plinth + shaft: the shaft's 40 rings (10 cm each) give the scene its triangle budget, as
// Sponza's many small pieces do, while one stored copy serves all 40 columns.
Mesh columnMesh() {
  Mesh column = makeCylinder(kPlinthRadius, kStageHeight, 32, 1, true);
  Mesh shaft = makeCylinder(kShaftRadius, kSpringHeight - 2 * kStageHeight, 64, 40, false);
  transformMesh(shaft, glm::translate(glm::mat4(1.0f), {0, kStageHeight, 0}));
  appendMesh(column, shaft);
  return column;
}

// Columns, capitals and arches of both colonnades on both storeys.
void addColonnades(Scene& scene, const AtriumMaterials& mat) {
  const int column = addMesh(scene, columnMesh(), "column", mat.stone);
  Mesh capitalMesh = makeCylinder(kPlinthRadius, kStageHeight, 32, 1, true);
  transformMesh(capitalMesh, glm::translate(glm::mat4(1.0f), {0, kSpringHeight - kStageHeight, 0}));
  const int capital = addMesh(scene, std::move(capitalMesh), "capital", mat.bronze);
  const int arch =
      addMesh(scene, makeArch(kArchInner, kArchThickness, 2 * kShaftRadius, 64), "arch", mat.stone);
  for (int storey = 0; storey < 2; ++storey)
    for (const float x : {-kColumnX, kColumnX}) {
      const float y = storey * kStoreyHeight;
      const std::string tag = std::to_string(storey) + (x < 0 ? "L" : "R");
      for (int i = 0; i < kColumnsPerRow; ++i) {
        const glm::mat4 at = glm::translate(glm::mat4(1.0f), {x, y, columnZ(i)});
        addInstance(scene, column, at, "column-" + tag + std::to_string(i));
        addInstance(scene, capital, at, "capital-" + tag + std::to_string(i));
      }
      // The arch is built in the XY plane; turned 90 degrees it spans along the nave (Z).
      for (int i = 0; i + 1 < kColumnsPerRow; ++i)
        addInstance(scene, arch,
                    translateRotateY({x, y + kSpringHeight, columnZ(i) + 0.5f * kBay}, 90.0f),
                    "arch-" + tag + std::to_string(i));
    }
}

// A box of the given size centred at the origin in x and z, from y = 0 up, so that one stored
// copy serves both sides by translation (mirroring would flip the winding of instances).
Mesh slabMesh(const glm::vec3& size) {
  return makeBox({-0.5f * size.x, 0, -0.5f * size.z}, {0.5f * size.x, size.y, 0.5f * size.z});
}

// Two copies placed point-symmetrically about the nave's axis, (x, z) -> (-x, -z): every
// shape here is symmetric itself, so a translation suffices.
void addSymmetricPair(Scene& scene, int mesh, const glm::vec3& right, const std::string& node) {
  addInstance(scene, mesh, glm::translate(glm::mat4(1.0f), right), node + "-R");
  addInstance(scene, mesh, glm::translate(glm::mat4(1.0f), right * glm::vec3(-1, 1, -1)),
              node + "-L");
}

// Gallery floors over the aisles, cornices over the upper arches, outer and end walls.
// The roof stays open: the sky lights the nave from above.
void addShell(Scene& scene, const AtriumMaterials& mat) {
  constexpr float kWall = 0.3f, kLength = 2 * kHalfLength;
  const float slabIn = kColumnX - kShaftRadius, slabWidth = kWallX - slabIn;
  const int slab =
      addMesh(scene, slabMesh({slabWidth, kSlabThickness, kLength}), "gallery-slab", mat.stone);
  addSymmetricPair(scene, slab, {slabIn + 0.5f * slabWidth, kStoreyHeight - kSlabThickness, 0},
                   "gallery");
  const int cornice =
      addMesh(scene, slabMesh({2 * kShaftRadius, 0.5f, kLength}), "cornice", mat.stone);
  addSymmetricPair(scene, cornice, {kColumnX, kRoofLine - 0.5f, 0}, "cornice");
  const int side = addMesh(scene, slabMesh({kWall, kRoofLine, kLength}), "side-wall", mat.plaster);
  addSymmetricPair(scene, side, {kWallX + 0.5f * kWall, 0, 0}, "side-wall");
  const int end =
      addMesh(scene, slabMesh({2 * (kWallX + kWall), kRoofLine, kWall}), "end-wall", mat.plaster);
  addSymmetricPair(scene, end, {0, 0, kHalfLength + 0.5f * kWall}, "end-wall");
}

// Bronze balustrade between the upper columns: balusters every 20 cm and a handrail per bay.
void addBalustrade(Scene& scene, const AtriumMaterials& mat) {
  constexpr float kHeight = 0.95f, kSpacing = 0.2f, kClear = kPlinthRadius + 0.05f;
  const int baluster =
      addMesh(scene, makeCylinder(0.025f, kHeight, 12, 1, true), "baluster", mat.bronze);
  Mesh railMesh = makeCylinder(0.04f, kBay - 2 * kClear, 16, 1, true);
  // Lay the rail along +Z, centred on the origin, at the balusters' top.
  transformMesh(railMesh,
                glm::translate(glm::mat4(1.0f), {0, kHeight, -0.5f * (kBay - 2 * kClear)}) *
                    glm::rotate(glm::mat4(1.0f), 0.5f * kPi, glm::vec3(1, 0, 0)));
  const int rail = addMesh(scene, std::move(railMesh), "handrail", mat.bronze);
  const int perBay = int((kBay - 2 * kClear) / kSpacing) + 1;
  for (const float x : {-kColumnX, kColumnX})
    for (int bay = 0; bay + 1 < kColumnsPerRow; ++bay) {
      const float z0 = columnZ(bay) + kClear, mid = columnZ(bay) + 0.5f * kBay;
      const std::string tag = (x < 0 ? "L" : "R") + std::to_string(bay);
      addInstance(scene, rail, glm::translate(glm::mat4(1.0f), {x, kStoreyHeight, mid}),
                  "handrail-" + tag);
      for (int k = 0; k < perBay; ++k)
        addInstance(scene, baluster,
                    glm::translate(glm::mat4(1.0f), {x, kStoreyHeight, z0 + k * kSpacing}),
                    "baluster-" + tag + "-" + std::to_string(k));
    }
}

// Alpha-masked lattice screens closing the first and last ground-floor bays of both arcades.
void addScreens(Scene& scene, const AtriumMaterials& mat) {
  const float width = kBay - 2 * kPlinthRadius;  // clear of plinths and capitals
  const int screen =
      addMesh(scene, makeQuad({0, 0, -0.5f * width}, {0, 0, width}, {0, kSpringHeight, 0}),
              "lattice-screen", mat.lattice);
  const float firstBay = columnZ(0) + 0.5f * kBay;
  addSymmetricPair(scene, screen, {kColumnX, 0, firstBay}, "screen-a");
  addSymmetricPair(scene, screen, {kColumnX, 0, -firstBay}, "screen-b");
}

// Warm lamps hanging along the nave. 40 cd at 3.2 m gives ~4 lux under each lamp, so the
// polished floor (albedo ~0.8) reads ~0.9 at exposure 1, like the sunlit scenes.
void addNaveLamps(Scene& scene) {
  constexpr float kCandela = 40.0f, kHeight = 3.2f;
  for (int i = 0; i < 4; ++i) {
    Light lamp;
    lamp.type = Light::Type::Point;
    lamp.name = "nave-lamp-" + std::to_string(i);
    lamp.color = glm::vec3(1.0f, 0.72f, 0.42f);  // ~2700 K, incandescent
    lamp.intensity = kCandela;
    lamp.position = glm::vec3(0.0f, kHeight, -15.0f + 10.0f * i);
    scene.lights.push_back(lamp);
  }
}

Scene makeAtrium() {
  Scene scene;
  scene.name = "atrium";
  const AtriumMaterials mat = addAtriumMaterials(scene);
  addStatic(scene,
            makeQuad({-kWallX, 0, kHalfLength}, {2 * kWallX, 0, 0}, {0, 0, -2 * kHalfLength}),
            "floor", mat.floor);
  addColonnades(scene, mat);
  addShell(scene, mat);
  addBalustrade(scene, mat);
  addScreens(scene, mat);
  addNaveLamps(scene);
  scene.environment = clearSky();
  // Eye height in the nave near the front wall, looking down its length and slightly up
  // so the gallery and the open roof are in view.
  scene.cameras.push_back(lookAtCamera("atrium-view", {0, 1.7f, 17.0f}, {0, 3.0f, 0}, 60.0f));
  return scene;
}

using SceneMaker = Scene (*)();

SceneMaker findMaker(const std::string& name) {
  if (name == "atrium") return makeAtrium;
  if (name == "cornell") return makeCornell;
  if (name == "spheres") return makeSpheres;
  return nullptr;
}

}  // namespace

std::vector<std::string> builtinSceneNames() {
  return {"atrium", "cornell", "spheres"};
}

bool isBuiltinScene(const std::string& name) {
  const std::vector<std::string> names = builtinSceneNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

Scene makeCornellTexturedLight() {
  Scene scene = makeCornell();
  scene.name = "cornell-textured-light";
  Mesh panel;
  const float cell = 2.0f / kPanelCells;
  for (int j = 0; j < kPanelCells; ++j)
    for (int i = 0; i < kPanelCells; ++i)
      appendMesh(panel, makeQuad({-1 + i * cell, 2.0f - 0.001f, -1 + j * cell}, {cell, 0, 0},
                                 {0, 0, cell}));
  for (size_t k = 0; k < panel.positions.size(); ++k)
    panel.uv0[k] = {0.5f * (panel.positions[k].x + 1), 0.5f * (panel.positions[k].z + 1)};
  scene.textures.push_back(panelTexture());
  Material m = cornellLight();
  m.name = "panel-light";
  // The lit square is (2 m x kPanelLit / kPanelTexels)^2, the cornell light 0.5 m square:
  // the same power.
  const float litSide = 2.0f * kPanelLit / kPanelTexels;
  m.emissiveStrength *= (kCornellLightSize * kCornellLightSize) / (litSide * litSide);
  m.emissiveTexture.texture = int(scene.textures.size() - 1);
  panel.name = "panel-light";
  panel.material = addMaterial(scene, m);
  for (const Instance& inst : scene.instances)  // the panel takes the light's place
    if (inst.node == "cornell-light") scene.meshes[size_t(inst.mesh)] = panel;
  return scene;
}

Scene makeBuiltinScene(const std::string& name) {
  const SceneMaker make = findMaker(name);
  if (!make) {
    std::string valid;
    for (const std::string& n : builtinSceneNames()) valid += (valid.empty() ? "" : ", ") + n;
    throw UsageError("unknown built-in scene '" + name + "' (valid: " + valid + ")");
  }
  return make();
}

}  // namespace photovr
