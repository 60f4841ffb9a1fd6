// The Embree side of a Scene: one triangle geometry per Mesh in its own BVH, referenced by
// one instance geometry per Scene instance in a top-level BVH (two-level, as the scene
// instances them). Embree types stay inside trace/.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "trace/work_skips.h"

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
  size_t filteredMeshes = 0;    // meshes with the any-hit filter installed
  std::string buildQuality;
  double buildMilliseconds = 0.0;
};

// One ray as the tracer handed it to Embree, for replaying the same ray mix through raw
// rtcIntersect1 / rtcOccluded1 (bench/).
struct RecordedRay {
  enum class Kind : uint8_t { Intersect, Occluded };
  glm::vec3 origin{0.0f};
  float tnear = 0.0f;
  glm::vec3 dir{0.0f};
  float tfar = 0.0f;
  Kind kind = Kind::Intersect;
};

// Collects every ray an EmbreeScene traces while attached to it, into one buffer per thread
// (so recording is safe inside the tracer's parallel tiles). With one thread the rays come
// back in exactly the order they were cast.
class RayRecorder {
 public:
  RayRecorder();
  ~RayRecorder();
  RayRecorder(const RayRecorder&) = delete;
  RayRecorder& operator=(const RayRecorder&) = delete;

  void record(const RecordedRay& ray);
  // Everything recorded so far, thread by thread, each in its own order; clears the buffers.
  std::vector<RecordedRay> take();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// What a replay found, so that its work cannot be skipped and can be checked.
struct ReplayCounts {
  uint64_t intersectRays = 0, hits = 0;
  uint64_t occludedRays = 0, blocked = 0;
};

class EmbreeScene {
 public:
  // Keeps a reference to 'scene': it must outlive this object. The any-hit filter goes only
  // on meshes that need it (MASK or single-sided), unless skips.anyHitFilter is off.
  explicit EmbreeScene(const Scene& scene, const WorkSkips& skips = {});
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

  // While set, intersect() and occluded() append each ray to 'recorder' (null: off; the
  // cost when off is one predictable branch per ray). Not to be changed during a render.
  void setRecorder(RayRecorder* recorder) { recorder_ = recorder; }

  // Traces 'count' recorded rays with bare rtcIntersect1 / rtcOccluded1 calls on this
  // scene (same BVHs, same filters), with no recording and no TraceHit conversion: the
  // traversal cost alone. Thread-safe; the caller sets flush-to-zero as tracing threads do.
  ReplayCounts replay(const RecordedRay* rays, size_t count) const;
  // The same on every thread: chunks of consecutive rays (one pixel's paths, then the next
  // pixel's) stay on one thread, as in the tracer's tiles, so coherence matches the render.
  ReplayCounts replayParallel(const std::vector<RecordedRay>& rays) const;

  const EmbreeStats& stats() const { return stats_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  EmbreeStats stats_;
  RayRecorder* recorder_ = nullptr;
};

// Flush-to-zero and denormals-are-zero for the calling thread (Embree's advice for speed;
// platform.md). Every tracing thread calls it once.
void enableFlushToZero();

}  // namespace photovr
