#include "trace/lights.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <limits>

#include "trace/surface.h"

namespace photovr {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Flux estimates, only used to choose between lights (any positive weights keep the
// estimator unbiased; proportional to power keeps its variance low).
// A directional light's flux is its irradiance over the scene's cross-section, pi R^2, the
// same disc the environment's estimate uses; weighting it by pi alone made a 5 lux sun 40x
// less likely to be picked than the sky in the spheres scene, and its shadows noisy.
float punctualPower(const Light& l, float sceneRadius) {
  const float i = luminance(l.color) * l.intensity;
  return l.type == Light::Type::Directional ? i * kPi * sceneRadius * sceneRadius : 4.0f * kPi * i;
}

float sceneRadius(const Scene& scene) {
  const Bounds b = scene.worldBounds();
  return b.empty() ? 1.0f : std::max(0.5f * glm::length(b.extent()), 1e-3f);
}

// glTF KHR_lights_punctual, "Range Property": smooth window to zero at 'range'.
float rangeWindow(float distance, float range) {
  if (range <= 0.0f) return 1.0f;
  const float r = distance / range, r4 = r * r * r * r;
  const float w = std::clamp(1.0f - r4, 0.0f, 1.0f);
  return w * w;
}

// glTF KHR_lights_punctual, "Inner and Outer Cone Angles": the reference smooth falloff,
// t^2 for t = clamp((cos(angle to the axis) - cos(outer)) * coneScale), coneScale =
// 1 / (cos(inner) - cos(outer)); 'toPoint' unit.
float spotFalloff(const glm::vec3& axis, float cosOuter, float coneScale,
                  const glm::vec3& toPoint) {
  const float t = std::clamp((glm::dot(axis, toPoint) - cosOuter) * coneScale, 0.0f, 1.0f);
  return t * t;
}

// The triangle's vertices in a canonical (sorted) order, to recognise duplicates.
std::array<float, 9> vertexKey(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  std::array<std::array<float, 3>, 3> v = {{{a.x, a.y, a.z}, {b.x, b.y, b.z}, {c.x, c.y, c.z}}};
  std::sort(v.begin(), v.end());
  return {v[0][0], v[0][1], v[0][2], v[1][0], v[1][1], v[1][2], v[2][0], v[2][1], v[2][2]};
}

// Largest number of points a textured emitter's power is estimated from.
constexpr int kMaxEmissionPoints = 64;

// Mean luminance of what triangle t of 'inst' emits from its front, over the triangle: the
// emission factor alone without an emissive texture; with one, a stratified average over
// about one point per texel the triangle covers (at most kMaxEmissionPoints), through the
// same texture lookups shading uses. The light set's weights need not be exact to stay
// unbiased (any positive weight for a triangle that emits is), only close for low variance;
// a triangle measured black is left out of the set, which is unbiased too: BSDF rays still
// find it, with MIS weight 1 where the light set does not hold it (pdfArea 0).
float meanEmission(const Scene& scene, uint32_t instance, uint32_t t, const glm::vec3& normal) {
  const Mesh& mesh = scene.meshes[scene.instances[instance].mesh];
  const Material& mat = scene.materials[mesh.material];
  const TextureRef& emissive = mat.unlit ? mat.baseColorTexture : mat.emissiveTexture;
  // What varies over the triangle: the emission texture, else (MASK, BLEND) the alpha's.
  const bool opaque = mat.alphaMode == AlphaMode::Opaque;
  const TextureRef& ref = emissive.valid() || opaque ? emissive : mat.baseColorTexture;
  if (!ref.valid() && opaque) return luminance(mat.emission());
  const std::vector<glm::vec2>& uv = ref.texCoord == 1 ? mesh.uv1 : mesh.uv0;
  int points = 1;
  if (ref.valid() && uv.size() == mesh.positions.size()) {
    const uint32_t* idx = &mesh.indices[3 * size_t(t)];
    const glm::vec2 d1 = uv[idx[1]] - uv[idx[0]], d2 = uv[idx[2]] - uv[idx[0]];
    const Texture& tex = scene.textures[size_t(ref.texture)];
    const float texels = 0.5f * std::abs(d1.x * d2.y - d1.y * d2.x) * float(tex.width) * tex.height;
    points = int(std::clamp(std::ceil(texels), 1.0f, float(kMaxEmissionPoints)));
  }
  float sum = 0.0f;
  for (int k = 0; k < points; ++k) {
    // Stratified in the first coordinate, golden-ratio in the second, mapped uniformly onto
    // the triangle as sampleTriangle maps its numbers (pbrt 3rd ed. §13.6.4).
    const float ux = (float(k) + 0.5f) / float(points);
    const float uy = std::fmod(0.5f + float(k) * 0.6180339887f, 1.0f);
    const float su = std::sqrt(ux);
    const float b1 = su * (1.0f - uy), b2 = su * uy;
    sum += luminance(emissionAt(scene, instance, t, b1, b2, normal, -normal)) *
           coverageAt(scene, instance, t, b1, b2);
  }
  return sum / float(points);
}

}  // namespace

LightSet::LightSet(const Scene& scene, const WorkSkips& skips) : scene_(scene), skips_(skips) {
  if (scene.environment.type != Environment::Type::None)
    environment_ = EnvironmentSampler(scene.environment);
  update();
}

// Everything but the environment's own sampler depends on where things are: the emitters'
// world triangles, and the selection weights (the scene's radius enters the punctual and
// environment powers).
void LightSet::update() {
  punctual_.clear(), triangles_.clear(), triangleSlots_.clear(), standIns_.clear();
  environmentIndex_ = -1;
  std::vector<float> weights;
  const float radius = sceneRadius(scene_);
  for (const Light& l : scene_.lights)
    if (l.intensity > 0.0f && luminance(l.color) > 0.0f) {
      const float cosOuter = std::cos(l.outerConeAngle), cosInner = std::cos(l.innerConeAngle);
      punctual_.push_back({&l, l.color * l.intensity, glm::normalize(l.direction), cosOuter,
                           1.0f / std::max(1e-4f, cosInner - cosOuter)});
      weights.push_back(punctualPower(l, radius));
    }
  addAreaTriangles(weights);
  addEnvironment(radius, weights);
  addStandIns(skips_, weights);
  selection_ = weights.empty() ? Distribution1D() : Distribution1D(weights);
  selectionPmf_.resize(weights.size());
  for (size_t i = 0; i < weights.size(); ++i) selectionPmf_[i] = selection_.pmf(int(i));
}

void LightSet::addAreaTriangles(std::vector<float>& weights) {
  const Scene& scene = scene_;
  instanceSlots_.assign(scene.instances.size(), kNoLight);
  // Coincident emitters (a triangle listed twice) are one light: a BSDF ray sees only one
  // of them, so sampling both would count the emission twice (stress suite, "duplicate").
  std::map<std::array<float, 9>, uint32_t> seen;
  for (uint32_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& inst = scene.instances[i];
    const Mesh& mesh = scene.meshes[inst.mesh];
    const Material& mat = scene.materials[mesh.material];
    if (!mat.isEmissive()) continue;
    instanceSlots_[i] = uint32_t(triangleSlots_.size());
    triangleSlots_.resize(triangleSlots_.size() + mesh.triangleCount(), kNoLight);
    for (uint32_t t = 0; t < mesh.triangleCount(); ++t) {
      const uint32_t* idx = &mesh.indices[3 * size_t(t)];
      const glm::vec3 p0 = glm::vec3(inst.transform * glm::vec4(mesh.positions[idx[0]], 1.0f));
      const glm::vec3 e1 = glm::vec3(inst.transform * glm::vec4(mesh.positions[idx[1]], 1.0f)) - p0;
      const glm::vec3 e2 = glm::vec3(inst.transform * glm::vec4(mesh.positions[idx[2]], 1.0f)) - p0;
      const float area = 0.5f * glm::length(glm::cross(e1, e2));
      if (!(area > 0.0f)) continue;
      const glm::vec3 normal = unitGeometricNormal(e1, e2);
      const float emitted =
          skips_.darkEmitters ? meanEmission(scene, i, t, normal) : luminance(mat.emission());
      if (!(emitted > 0.0f)) continue;  // black under its texture: see meanEmission
      const auto [it, fresh] =
          seen.try_emplace(vertexKey(p0, p0 + e1, p0 + e2), uint32_t(triangles_.size()));
      triangleSlots_[instanceSlots_[i] + t] = it->second;
      if (!fresh) continue;
      triangles_.push_back({i, t, p0, e1, e2, normal, area});
      weights.push_back(emitted * area * kPi * (mat.doubleSided ? 2.0f : 1.0f));
    }
  }
}

// Flux the environment sends through the scene's bounding disc: pi L_avg * pi R^2, with
// L_avg from a fixed 8 x 8 stratified set of directions (deterministic).
void LightSet::addEnvironment(float radius, std::vector<float>& weights) {
  if (environment_.empty()) return;
  float avg = 0.0f;
  for (int k = 0; k < 64; ++k) {
    const glm::vec3 d = sampleUniformSphere({(k % 8 + 0.5f) / 8.0f, (k / 8 + 0.5f) / 8.0f});
    avg += luminance(lookupEnvironment(scene_.environment, d)) / 64.0f;
  }
  environmentIndex_ = int(weights.size());
  weights.push_back(std::max(avg, 1e-6f) * kPi * kPi * radius * radius);
}

void LightSet::addStandIns(const WorkSkips& skips, std::vector<float>& weights) {
  const Bounds b = scene_.worldBounds();
  sceneCentre_ = b.empty() ? glm::vec3(0.0f) : b.center();
  if (!skips.punctualLights && punctual_.empty()) standIns_.push_back(StandIn::Punctual);
  if (!skips.areaLights && triangles_.empty()) standIns_.push_back(StandIn::Area);
  if (!skips.environment && environmentIndex_ < 0) standIns_.push_back(StandIn::Environment);
  // A renderer that cannot know a light is dark gives it a typical share: the mean weight.
  float mean = 1.0f;
  if (!weights.empty()) {
    mean = 0.0f;
    for (float w : weights) mean += w / float(weights.size());
  }
  weights.insert(weights.end(), standIns_.size(), mean);
}

void LightSet::sampleStandIn(StandIn kind, const glm::vec3& point, glm::vec2 u,
                             LightSample& s) const {
  if (kind == StandIn::Environment) {
    s.direction = sampleUniformSphere(u);
    s.distance = kInfinity;
    s.pdf = 1.0f / (4.0f * kPi);
    return;  // radiance 0: the shadow ray is still cast
  }
  const glm::vec3 d = sceneCentre_ - point;
  const float dist = glm::length(d);
  if (!(dist > 0.0f)) return;
  s.direction = d / dist;
  s.distance = dist;
  s.isDelta = kind == StandIn::Punctual;
  s.isArea = kind == StandIn::Area;
  s.pdf = 1.0f;  // nominal: the radiance is 0 whatever the density
}

void LightSet::samplePunctual(const Punctual& p, const glm::vec3& point, LightSample& s) const {
  const Light& l = *p.light;
  s.isDelta = true;
  if (l.type == Light::Type::Directional) {
    s.direction = -p.axis;
    s.distance = kInfinity;
    s.radiance = p.radiance;  // lux: irradiance normal to the light
    return;
  }
  const glm::vec3 d = l.position - point;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f)) return;
  s.distance = std::sqrt(dist2);
  s.direction = d / s.distance;
  float scale = rangeWindow(s.distance, l.range) / dist2;  // candela / d^2 = irradiance
  if (l.type == Light::Type::Spot)
    scale *= spotFalloff(p.axis, p.cosOuter, p.coneScale, -s.direction);
  s.radiance = p.radiance * scale;
}

void LightSet::sampleTriangle(const AreaTriangle& tri, const glm::vec3& point, glm::vec2 u,
                              LightSample& s) const {
  // Uniform point on the triangle (Pharr, Jakob, Humphreys, pbrt 3rd ed. §13.6.4).
  const float su = std::sqrt(u.x);
  const float b1 = su * (1.0f - u.y), b2 = su * u.y;
  const glm::vec3 p = tri.p0 + b1 * tri.e1 + b2 * tri.e2;
  s.isArea = true;
  const glm::vec3 d = p - point;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f)) return;
  s.distance = std::sqrt(dist2);
  s.direction = d / s.distance;
  const float cosLight = std::abs(glm::dot(tri.normal, s.direction));
  if (!(cosLight > 0.0f)) return;
  // Times the emitter's coverage: BSDF rays meet a BLEND emitter with probability alpha and
  // never a MASK hole, so NEE counts it as much (without it, NEE + MIS counted a BLEND
  // emitter's light between alpha and 1 times).
  s.radiance = emissionAt(scene_, tri.instance, tri.triangle, b1, b2, tri.normal, s.direction) *
               coverageAt(scene_, tri.instance, tri.triangle, b1, b2);
  if (s.radiance == glm::vec3(0.0f)) return;
  s.pdf = dist2 / (cosLight * tri.area);  // area density converted to solid angle
}

void LightSet::sample(const glm::vec3& point, float uSelect, glm::vec2 u, LightSample& s) const {
  s = LightSample{};
  if (empty()) return;
  const int pick = selection_.sampleIndex(uSelect);
  const int n = int(punctual_.size()), m = int(triangles_.size());
  const int firstStandIn = n + m + (environmentIndex_ >= 0 ? 1 : 0);
  if (pick >= firstStandIn) {
    sampleStandIn(standIns_[pick - firstStandIn], point, u, s);
  } else if (pick < n) {
    samplePunctual(punctual_[pick], point, s);
    s.pdf = s.radiance == glm::vec3(0.0f) ? 0.0f : 1.0f;
  } else if (pick < n + m) {
    sampleTriangle(triangles_[pick - n], point, u, s);
  } else {
    const EnvironmentSample e = environment_.sample(u);
    s.direction = e.direction;
    s.distance = kInfinity;
    s.radiance = e.radiance;
    s.pdf = e.pdf;
  }
  s.pdf *= selectionPmf_[size_t(pick)];
}

float LightSet::pdfArea(uint32_t instance, uint32_t triangle, const glm::vec3& from,
                        const glm::vec3& lightPoint, const glm::vec3& lightNormal) const {
  const uint32_t index = lightIndex(instance, triangle);
  if (index == kNoLight) return 0.0f;
  const AreaTriangle& tri = triangles_[index];
  const glm::vec3 d = lightPoint - from;
  const float dist2 = glm::dot(d, d);
  const float cosLight = std::abs(glm::dot(lightNormal, d)) / std::sqrt(dist2);
  if (!(cosLight > 0.0f)) return 0.0f;
  return selectionPmf_[punctual_.size() + index] * dist2 / (cosLight * tri.area);
}

uint32_t LightSet::lightIndex(uint32_t instance, uint32_t triangle) const {
  if (instance >= instanceSlots_.size() || instanceSlots_[instance] == kNoLight) return kNoLight;
  return triangleSlots_[instanceSlots_[instance] + triangle];
}

float LightSet::pdfEnvironment(const glm::vec3& dir) const {
  if (environmentIndex_ < 0) return 0.0f;
  return selectionPmf_[size_t(environmentIndex_)] * environment_.pdf(dir);
}

glm::vec3 LightSet::environmentRadiance(const glm::vec3& dir) const {
  return lookupEnvironment(scene_.environment, dir);
}

}  // namespace photovr
