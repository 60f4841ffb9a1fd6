// The Embree side of a Scene: one triangle geometry per Mesh in its own BVH, referenced by
// one instance geometry per Scene instance in a top-level BVH (two-level, as the scene
// instances them). Embree types stay inside trace/.
#pragma once

#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace photovr {

struct TraceHit {
  bool hit = false;
  float t = 0.0f;
  uint32_t instance = 0;  // index into Scene::instances
  uint32_t triangle = 0;
  float b1 = 0.0f, b2 = 0.0f;  // barycentrics of vertices 1 and 2 (Embree's u, v)
};

struct EmbreeStats {
  size_t meshBvhs = 0;
  size_t instances = 0;
  bool alphaFilter = false;     // any-hit alpha test installed (scene has MASK materials)
  bool backFaceFilter = false;  // any-hit back-face culling (single-sided materials)
  std::string buildQuality;
  double buildMilliseconds = 0.0;
};

class EmbreeScene {
 public:
  // Keeps a reference to 'scene': it must outlive this object.
  explicit EmbreeScene(const Scene& scene);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Closest hit in (tnear, tfar).
  TraceHit intersect(const glm::vec3& origin, const glm::vec3& dir, float tnear, float tfar) const;
  // Any hit in (tnear, tfar).
  bool occluded(const glm::vec3& origin, const glm::vec3& dir, float tnear, float tfar) const;

  // Instance transforms changed (not the meshes): re-commits only the top level, whose
  // LOW-quality dynamic BVH Embree refits/rebuilds in ~0.05 ms per 100 instances
  // (platform.md), instead of rebuilding any mesh BVH.
  void updateInstanceTransforms();

  const EmbreeStats& stats() const { return stats_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  EmbreeStats stats_;
};

// Flush-to-zero and denormals-are-zero for the calling thread (Embree's advice for speed;
// platform.md). Every tracing thread calls it once.
void enableFlushToZero();

}  // namespace photovr
