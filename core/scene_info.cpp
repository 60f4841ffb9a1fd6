#include "core/scene_info.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <utility>

#include "core/bvh_layout.h"
#include "core/scene_transform.h"

namespace photovr {
namespace {

// 1234567 -> "1,234,567": triangle counts are read at a glance.
std::string count(size_t n) {
  std::string digits = std::to_string(n), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string fmt(const char* format, double a, double b = 0, double c = 0) {
  char buf[128];
  std::snprintf(buf, sizeof buf, format, a, b, c);
  return buf;
}

std::string vec(const glm::vec3& v) {
  return fmt("(%.2f, %.2f, %.2f)", v.x, v.y, v.z);
}

const Material* materialOf(const Scene& scene, const Mesh& mesh) {
  const bool ok = mesh.material >= 0 && size_t(mesh.material) < scene.materials.size();
  return ok ? &scene.materials[mesh.material] : nullptr;
}

void addMaterialFlags(SceneFeatures& f, const Material& m, size_t triangles) {
  if (m.isEmissive()) f.emissiveTriangles += triangles;
  f.unlitSurfaces |= m.unlit && glm::vec3(m.baseColorFactor) != glm::vec3(0.0f);
  f.alphaMask |= m.alphaMode == AlphaMode::Mask;
  f.alphaBlend |= m.alphaMode == AlphaMode::Blend;
  f.doubleSided |= m.doubleSided;
  f.singleSided |= m.cullsBackFaces();
}

void countLights(SceneFeatures& f, const Scene& scene) {
  for (const Light& l : scene.lights) {
    if (l.type == Light::Type::Point) ++f.pointLights;
    if (l.type == Light::Type::Spot) ++f.spotLights;
    if (l.type == Light::Type::Directional) ++f.directionalLights;
  }
  f.punctualLights = !scene.lights.empty();
}

bool environmentEmits(const Environment& env) {
  switch (env.type) {
    case Environment::Type::None:
      return false;
    case Environment::Type::Map:
      return !env.pixels.empty() && env.intensity > 0.0f;
    default:
      return env.intensity > 0.0f;
  }
}

// photovr traces and rasterises in world-space floats: far from the origin their spacing
// (2^-23 of the coordinate, about) snaps vertices. Below 1/4096 of the scene's extent per
// step the snapping stays under the offsets rays leave surfaces by; above, a 1e7 m scene
// measured visibly wrong (issue 23: a 1 m grid, a Cornell box's short block gone).
constexpr double kMaxSpacingOverExtent = 1.0 / 4096.0;

// The farthest coordinate of 'b' from zero and its diagonal.
std::pair<double, double> reachAndExtent(const Bounds& b) {
  const glm::vec3 far = glm::max(glm::abs(b.min), glm::abs(b.max));
  return {std::max({double(far.x), double(far.y), double(far.z)}),
          glm::length(glm::dvec3(b.extent()))};
}

double floatSpacingAt(double reach) {
  return double(std::nextafter(float(reach), INFINITY)) - double(float(reach));
}

// World coordinates: a loaded file is re-based near its content (storePlacement), so this
// is for scenes built or moved in code in float.
std::string farFromOriginWarning(const Scene& scene) {
  const auto [reach, extent] = reachAndExtent(scene.worldBounds());
  if (!floatsTooCoarse(reach, extent, kMaxSpacingOverExtent)) return "";
  const double spacing = floatSpacingAt(reach);
  char text[240];
  std::snprintf(text, sizeof text,
                "geometry lies up to %.3g m from the origin, where floats are %.3g m apart "
                "(1/%.0f of the scene's %.3g m extent): vertices snap to that grid; move the "
                "scene near the origin",
                reach, spacing, extent / spacing, extent);
  return text;
}

// A mesh's own vertex data, stored in float in the file: no re-basing recovers what was
// lost there. One warning for the worst mesh.
std::string farVertexDataWarning(const Scene& scene) {
  const Mesh* worst = nullptr;
  double worstRatio = 0.0, worstReach = 0.0;
  for (const Mesh& m : scene.meshes) {
    Bounds b;
    for (const glm::vec3& p : m.positions) b.extend(p);
    if (b.empty()) continue;
    const auto [reach, extent] = reachAndExtent(b);
    if (!floatsTooCoarse(reach, extent, kMaxSpacingOverExtent)) continue;
    if (const double ratio = floatSpacingAt(reach) / extent; ratio > worstRatio) {
      worst = &m;
      worstRatio = ratio;
      worstReach = reach;
    }
  }
  if (!worst) return "";
  char text[280];
  std::snprintf(text, sizeof text,
                "mesh '%s' stores vertices up to %.3g m from its own origin, where floats are "
                "%.3g m apart (1/%.0f of its extent): that precision was lost in the file; "
                "export it with the offset in its node's transform",
                worst->name.c_str(), worstReach, floatSpacingAt(worstReach), 1.0 / worstRatio);
  return text;
}

void addWarnings(SceneFeatures& f, const Scene& scene, size_t badInstances, size_t unusedMeshes) {
  if (badInstances > 0)
    f.warnings.push_back(count(badInstances) + " instances name a mesh that does not exist");
  if (unusedMeshes > 0)
    f.warnings.push_back(count(unusedMeshes) + " meshes are used by no instance (not drawn)");
  if (!f.punctualLights && !f.areaLights && !f.environment && !f.unlitSurfaces)
    f.warnings.push_back("no light, emitter or environment: the image will be black");
  const Environment& env = scene.environment;
  if (env.type == Environment::Type::Map &&
      env.pixels.size() != size_t(env.width) * size_t(env.height))
    f.warnings.push_back("environment map pixel count does not match its size");
  if (scene.cameras.empty()) f.warnings.push_back("no camera in the scene");
  if (std::string far = farFromOriginWarning(scene); !far.empty()) f.warnings.push_back(far);
  if (std::string far = farVertexDataWarning(scene); !far.empty()) f.warnings.push_back(far);
}

// ---------------------------------------------------------------------------------------
// describeScene sections

void describeGeometry(std::ostream& out, const Scene& scene) {
  size_t vertices = 0, triangles = 0, instanced = 0, shared = 0;
  std::vector<size_t> uses(scene.meshes.size(), 0);
  for (const Mesh& m : scene.meshes) {
    vertices += m.vertexCount();
    triangles += m.triangleCount();
  }
  for (const Instance& inst : scene.instances)
    if (scene.hasMesh(inst.mesh)) {
      ++uses[inst.mesh];
      instanced += scene.meshes[inst.mesh].triangleCount();
    }
  for (const size_t u : uses) shared += u >= 2 ? 1 : 0;
  out << "meshes: " << count(scene.meshes.size()) << " (" << count(vertices) << " vertices, "
      << count(triangles) << " triangles stored)\n";
  out << "instances: " << count(scene.instances.size()) << " (" << count(instanced)
      << " triangles instanced; " << count(shared) << (shared == 1 ? " mesh" : " meshes")
      << " instanced more than once)\n";
  for (const Animation& a : scene.animations)
    out << "animation: '" << a.name << "', " << fmt("%.2f s", a.duration()) << ", "
        << a.channels.size()
        << " node channel(s) (render --time T poses it; --play, --hmd and view play it)\n";
  for (const Skin& skin : scene.skins) {
    size_t meshes = 0, vertices = 0;
    for (const Mesh& m : scene.meshes)
      if (m.skinning.skin == int(&skin - scene.skins.data())) ++meshes, vertices += m.vertexCount();
    out << "skin: '" << skin.name << "', " << skin.joints.size() << " joints, " << meshes
        << " mesh(es), " << count(vertices) << " vertices skinned on the CPU\n";
  }
}

void describeMaterials(std::ostream& out, const Scene& scene) {
  size_t emissive = 0, metal = 0, dielectric = 0, mixed = 0, mask = 0, blend = 0, twoSided = 0,
         glass = 0, coated = 0, sheen = 0;
  for (const Material& m : scene.materials) {
    emissive += m.isEmissive();
    metal += m.metallicFactor >= 1.0f;
    dielectric += m.metallicFactor <= 0.0f;
    mixed += m.metallicFactor > 0.0f && m.metallicFactor < 1.0f;
    mask += m.alphaMode == AlphaMode::Mask;
    blend += m.alphaMode == AlphaMode::Blend;
    twoSided += m.doubleSided;
    glass += m.transmissionFactor > 0.0f;
    coated += m.clearcoatFactor > 0.0f;
    sheen += m.sheenColorFactor != glm::vec3(0.0f);
  }
  out << "materials: " << count(scene.materials.size()) << " (emissive " << emissive << ", metal "
      << metal << ", dielectric " << dielectric << ", partly metallic " << mixed << ", MASK "
      << mask << ", BLEND " << blend << ", double-sided " << twoSided << ", transmissive " << glass
      << ", clear-coated " << coated << ", sheen " << sheen << ")\n";
  if (scene.extensions.empty()) return;
  out << "extensions:";
  for (const Scene::Extension& e : scene.extensions)
    out << " " << e.name << (e.read ? " (read)" : " (ignored)");
  out << "\n";
}

void describeTextures(std::ostream& out, const Scene& scene) {
  constexpr size_t kListed = 16;  // enough for built-ins; big glTF files get a count
  out << "textures: " << count(scene.textures.size()) << "\n";
  for (size_t i = 0; i < scene.textures.size() && i < kListed; ++i) {
    const Texture& t = scene.textures[i];
    out << "  " << t.name << " " << t.width << "x" << t.height << "\n";
  }
  if (scene.textures.size() > kListed)
    out << "  ... and " << count(scene.textures.size() - kListed) << " more\n";
}

void describeLights(std::ostream& out, const Scene& scene, const SceneFeatures& f) {
  out << "lights: " << count(scene.lights.size()) << " (point " << f.pointLights << ", spot "
      << f.spotLights << ", directional " << f.directionalLights << ")\n";
  out << "emissive triangles: " << count(f.emissiveTriangles) << " instanced\n";
}

void describeCameras(std::ostream& out, const Scene& scene) {
  out << "cameras: " << count(scene.cameras.size()) << "\n";
  for (const Camera& c : scene.cameras)
    out << "  " << c.name << " at " << vec(c.position) << ", yfov "
        << fmt("%.1f", glm::degrees(c.yfov)) << " deg\n";
}

std::string environmentName(const Environment& env) {
  switch (env.type) {
    case Environment::Type::None:
      return "none";
    case Environment::Type::Constant:
      return "constant " + vec(env.constant * env.intensity);
    case Environment::Type::Map:
      return "map " + std::to_string(env.width) + "x" + std::to_string(env.height);
    case Environment::Type::Sky: {
      const float elevation = glm::degrees(std::asin(glm::clamp(env.sunDirection.y, -1.f, 1.f)));
      return "sky (sun elevation " + fmt("%.1f", elevation) + " deg)";
    }
  }
  return "unknown";
}

void describeBounds(std::ostream& out, const Scene& scene) {
  const Bounds b = scene.worldBounds();
  if (b.empty()) {
    out << "world bounds: empty\n";
    return;
  }
  const glm::vec3 e = b.extent();
  out << "world bounds: " << vec(b.min) << " .. " << vec(b.max) << ", size "
      << fmt("%.2f x %.2f x %.2f m", e.x, e.y, e.z) << "\n";
  if (scene.origin != glm::dvec3(0.0))
    out << "origin: the file's "
        << fmt("(%.3f, %.3f, %.3f)", scene.origin.x, scene.origin.y, scene.origin.z)
        << " m (re-based there: floats at the file's coordinates were too coarse)\n";
}

// How trace/embree_scene.cpp lays out the BVHs (core/bvh_layout.h), and why.
void describeBvhLayout(std::ostream& out, const Scene& scene) {
  const BvhLayout l = bvhLayoutOf(scene);
  out << "  BVH: ";
  if (l.oneLevel)
    out << "one level (every instance's mesh in world space, " << fmt("%.2fx", l.copies)
        << " the stored triangles)\n";
  else if (l.moves)
    out << "two levels (the scene moves: the top level, and skinned meshes, are refit)\n";
  else if (scene.instances.empty())
    out << "none (no instance)\n";
  else
    out << "two levels (copying the shared meshes would take " << fmt("%.1fx", l.copies)
        << " the stored triangles, above " << fmt("%.0fx", kOneLevelCopies) << ")\n";
}

void describeRendererUse(std::ostream& out, const Scene& scene, const SceneFeatures& f) {
  out << "renderer will use:\n";
  out << "  punctual lights: "
      << (f.punctualLights ? count(scene.lights.size()) + " (shadow rays)"
                           : std::string("none (no shadow rays)"))
      << "\n";
  out << "  area lights: "
      << (f.areaLights ? count(f.emissiveTriangles) + " emissive triangles"
                       : std::string("none (no area-light sampling)"))
      << "\n";
  out << "  environment: "
      << (f.environment ? environmentName(scene.environment)
                        : std::string("none (misses are black)"))
      << "\n";
  out << "  alpha mask: " << (f.alphaMask ? "yes (any-hit filter)" : "no") << "\n";
  if (f.alphaBlend) out << "  alpha blend: stochastic coverage (any-hit filter, G-buffer hash)\n";
  out << "  double-sided: " << (f.doubleSided ? "yes" : "no") << "\n";
  out << "  any-hit filter: " << count(f.filteredMeshes) << " of " << count(scene.meshes.size())
      << " meshes (MASK or BLEND; the rest have none)\n";
  out << "  single-sided back faces: "
      << (f.singleSided ? "culled for camera rays (as rasterized), met by bounce and shadow rays"
                        : std::string("none (every material is double-sided)"))
      << "\n";
  describeBvhLayout(out, scene);
  out << (isAnimated(scene) ? "  BVH refit: once per frame while the animation plays (the top "
                              "level; skinned meshes' BVHs too); never for a still at --time\n"
                            : "  BVH refit: never (static scene)\n");
  out << "  sky pixels: "
      << (f.environment ? "environment looked up, not traced (hybrid)"
                        : std::string("black, not traced (hybrid)"))
      << "\n";
  out << "  (render --no-skip NAME|all turns these skips off, to measure them)\n";
}

void describeWarnings(std::ostream& out, const Scene& scene, const SceneFeatures& f) {
  const size_t n = f.warnings.size() + scene.warnings.size();
  out << "warnings: " << (n == 0 ? std::string("none") : count(n)) << "\n";
  for (const std::string& w : scene.warnings) out << "  " << w << "\n";
  for (const std::string& w : f.warnings) out << "  " << w << "\n";
}

}  // namespace

SceneFeatures analyzeScene(const Scene& scene) {
  SceneFeatures f;
  std::vector<bool> used(scene.meshes.size(), false);
  size_t badInstances = 0;
  for (const Instance& inst : scene.instances) {
    if (!scene.hasMesh(inst.mesh)) {
      ++badInstances;
      continue;
    }
    used[inst.mesh] = true;
    const Mesh& mesh = scene.meshes[inst.mesh];
    if (const Material* m = materialOf(scene, mesh)) addMaterialFlags(f, *m, mesh.triangleCount());
  }
  countLights(f, scene);
  f.areaLights = f.emissiveTriangles > 0;
  for (const Mesh& mesh : scene.meshes)  // as trace/embree_scene.cpp installs the filter
    if (const Material* m = materialOf(scene, mesh))
      f.filteredMeshes += m->alphaMode != AlphaMode::Opaque;
  f.environment = environmentEmits(scene.environment);
  size_t unused = 0;
  for (const bool u : used) unused += u ? 0 : 1;
  addWarnings(f, scene, badInstances, unused);
  return f;
}

std::string describeScene(const Scene& scene) {
  const SceneFeatures f = analyzeScene(scene);
  std::ostringstream out;
  out << "scene: " << scene.name << "\n";
  describeGeometry(out, scene);
  describeMaterials(out, scene);
  describeTextures(out, scene);
  describeLights(out, scene, f);
  describeCameras(out, scene);
  out << "environment: " << environmentName(scene.environment) << "\n";
  describeBounds(out, scene);
  describeRendererUse(out, scene, f);
  describeWarnings(out, scene, f);
  return out.str();
}

}  // namespace photovr
