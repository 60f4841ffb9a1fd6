// Every light the tracer samples for next-event estimation: KHR_lights_punctual (point,
// spot, directional), emissive triangles as area lights, and the environment. One light
// is picked per estimate, in proportion to an estimate of its power.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "trace/environment_sampling.h"
#include "trace/sampling.h"
#include "trace/work_skips.h"

namespace photovr {

struct LightSample {
  glm::vec3 direction{0.0f};  // unit, from the shaded point towards the light
  float distance = 0.0f;      // to the light point; infinity for directional / environment
  glm::vec3 radiance{0.0f};   // arriving at the shaded point (unoccluded), before 1/pdf
  float pdf = 0.0f;           // selection x solid-angle density; selection only for deltas
  bool isDelta = false;       // punctual: cannot be hit by BSDF rays, no MIS
  bool isArea = false;        // emissive triangle: shadow ray stops short of it
  bool valid() const { return pdf > 0.0f; }
  // A light at infinity (the environment, a directional light, their stand-ins): the same
  // sample, for the same numbers, from every point.
  bool atInfinity() const { return std::isinf(distance); }
};

class LightSet {
 public:
  // Keeps references to 'scene' (and its environment). With a light-class skip turned off
  // (work_skips.h), a class the scene lacks is represented by a dark stand-in.
  explicit LightSet(const Scene& scene, const WorkSkips& skips = {});
  // The scene moved (core/animation.h poseScene): the emitters' world triangles and the
  // selection weights are rebuilt from it; the environment's sampler stays.
  void update();

  bool empty() const { return selection_.size() == 0; }
  bool hasEnvironment() const { return !environment_.empty(); }
  size_t punctualCount() const { return punctual_.size(); }
  size_t areaTriangleCount() const { return triangles_.size(); }
  size_t standInCount() const { return standIns_.size(); }

  // Written into 'out': a sample returned through the stack stalled its reader on store
  // forwarding (Frame::setZ).
  void sample(const glm::vec3& point, float uSelect, glm::vec2 u, LightSample& out) const;
  LightSample sample(const glm::vec3& point, float uSelect, glm::vec2 u) const {
    LightSample s;
    sample(point, uSelect, u, s);
    return s;
  }

  // Densities of sample() for a direction found by BSDF sampling (for MIS):
  // an emissive triangle hit at 'lightPoint' with geometric normal 'lightNormal' ...
  float pdfArea(uint32_t instance, uint32_t triangle, const glm::vec3& from,
                const glm::vec3& lightPoint, const glm::vec3& lightNormal) const;
  // ... or the environment in direction 'dir'.
  float pdfEnvironment(const glm::vec3& dir) const;
  glm::vec3 environmentRadiance(const glm::vec3& dir) const;

 private:
  struct AreaTriangle {
    uint32_t instance, triangle;
    glm::vec3 p0, e1, e2;  // world
    glm::vec3 normal;      // world, unit: unitGeometricNormal(e1, e2), as surfaceAt's
    float area;
  };
  // A punctual light with what its samples share, computed once (with the expressions the
  // samples used: the same bits).
  struct Punctual {
    const Light* light;
    glm::vec3 radiance;         // colour x intensity
    glm::vec3 axis;             // unit, where it points
    float cosOuter, coneScale;  // a spot's cone: the falloff's offset and scale
  };
  static constexpr uint32_t kNoLight = ~0u;
  // Index into triangles_ of (instance, triangle), or kNoLight: a flat table instead of a
  // hash map, since pdfArea() runs for every BSDF ray that lands on an emitter.
  uint32_t lightIndex(uint32_t instance, uint32_t triangle) const;
  // Each fills a default LightSample 's'.
  void samplePunctual(const Punctual& light, const glm::vec3& point, LightSample& s) const;
  void sampleTriangle(const AreaTriangle& tri, const glm::vec3& point, glm::vec2 u,
                      LightSample& s) const;
  // A light class the scene lacks, sampled like a real light of that class but dark.
  enum class StandIn { Punctual, Area, Environment };
  void sampleStandIn(StandIn kind, const glm::vec3& point, glm::vec2 u, LightSample& s) const;
  void addAreaTriangles(std::vector<float>& weights);
  void addEnvironment(float radius, std::vector<float>& weights);
  void addStandIns(const WorkSkips& skips, std::vector<float>& weights);

  const Scene& scene_;
  WorkSkips skips_;
  std::vector<Punctual> punctual_;
  std::vector<AreaTriangle> triangles_;
  std::vector<uint32_t> instanceSlots_;  // per instance: first entry in triangleSlots_, or kNoLight
  std::vector<uint32_t> triangleSlots_;  // per triangle of emissive instances: light or kNoLight
  EnvironmentSampler environment_;
  int environmentIndex_ = -1;  // in selection_; -1: no environment sampler
  std::vector<StandIn> standIns_;
  glm::vec3 sceneCentre_{0.0f};
  // Over punctual_, then triangles_, then the environment, then standIns_.
  Distribution1D selection_;
  // selection_.pmf of each light, kept: its division was a third of sampleDiscrete's time
  // (perf annotate), on the path of every light sample and every MIS weight.
  std::vector<float> selectionPmf_;
};

}  // namespace photovr
