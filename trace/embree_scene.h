// The Embree side of a Scene: one triangle geometry per Mesh in its own BVH, referenced by
// one instance geometry per Scene instance in a top-level BVH (two-level, as the scene
// instances them); or, in a still scene whose shared meshes are cheap to copy, each instance's
// mesh in world space in one BVH (one level). Embree types stay inside trace/.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "trace/surface.h"
#include "trace/work_skips.h"

namespace photovr {

struct TraceHit {
  bool hit = false;
  float t = 0.0f;
  uint32_t instance = 0;  // index into Scene::instances
  uint32_t triangle = 0;
  float b1 = 0.0f, b2 = 0.0f;  // barycentrics of vertices 1 and 2 (Embree's u, v)
};

// Whose ray it is. Camera rays see single-sided surfaces from the front only, as the
// G-buffer's rasterizer does (glTF 3.9.5 culls their back faces), so that both modes agree
// on what an eye sees. Transport rays (bounce and shadow rays) meet every surface from both
// sides: a single-sided wall blocks light from behind as from in front, as in Cycles, and
// light does not leak through the back of a one-sided mesh (docs/ARCHITECTURE.md).
enum class RayRole : uint8_t { Transport, Camera };

struct EmbreeStats {
  size_t meshBvhs = 0;  // meshes with a BVH of their own, instanced
  size_t instances = 0;
  // Instances whose mesh is in the top level itself, copied into world space: all of them in a
  // still scene where no mesh is skinned and the copies at most double the stored triangles
  // (one BVH level), else none.
  size_t instancesInTopLevel = 0;
  bool alphaFilter = false;  // any-hit alpha test installed (scene has MASK or BLEND materials)
  // Camera rays cull single-sided back faces (the scene has single-sided meshes): a filter
  // in their intersect context, which transport rays go without.
  bool cameraBackFaceCulling = false;
  size_t filteredMeshes = 0;  // meshes with the any-hit (alpha) filter installed
  std::string buildQuality;
  double buildMilliseconds = 0.0;
};

// One ray as the tracer handed it to Embree, for replaying the same ray mix through raw
// rtcIntersect1 / rtcOccluded1 (bench/).
struct RecordedRay {
  enum class Kind : uint8_t { Intersect, Occluded, Camera };  // Camera: an intersect ray of it
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

// One ray of a batch, from 'origin' along 'dir' over (tnear, tfar), laid out as Embree's
// RTCRay (static_asserts in embree_scene.cpp), so a batch goes to Embree's stream calls in
// place: copying it into Embree's structures was 4 % of a render (bench_trace profile).
struct alignas(16) BatchRay {
  glm::vec3 origin{0.0f};
  float tnear = 0.0f;
  glm::vec3 dir{0.0f};
  float time = 0.0f;
  float tfar = 0.0f;  // after occludedBatch: -infinity where something blocks the ray
  uint32_t mask = ~0u, id = 0, flags = 0;

  static BatchRay make(const glm::vec3& origin, const glm::vec3& dir, float tnear, float tfar) {
    BatchRay r;
    r.set(origin, dir, tnear, tfar);
    return r;
  }
  // make(...), written in place: a BatchRay returned and assigned was built on the stack
  // by scalar stores and copied by 16-byte loads, which stalled on store forwarding (a
  // third of shadeVertex's time in bench_trace's profile).
  void set(const glm::vec3& from, const glm::vec3& along, float near, float far) {
    origin = from, dir = along, tnear = near, tfar = far;
    time = 0.0f, mask = ~0u, id = 0, flags = 0;
  }
  bool blocked() const { return tfar < 0.0f; }
};

// A ray with the closest hit Embree found for it (RTCRayHit's layout).
struct alignas(16) BatchRayHit {
  BatchRay ray;
  glm::vec3 ng{0.0f};  // unnormalised geometric normal, instance space
  float u = 0.0f, v = 0.0f;
  uint32_t primID = ~0u, geomID = ~0u, instID = ~0u;  // ~0u: RTC_INVALID_GEOMETRY_ID

  // A mesh in the top level (EmbreeScene) has no instance id: its geometry id is the instance.
  uint32_t instance() const { return instID != ~0u ? instID : geomID; }
  TraceHit traceHit() const {
    if (geomID == ~0u) return {};
    return {true, ray.tfar, instance(), primID, u, v};
  }
};

// How a batch goes to Embree. Stream: one rtcIntersect1M / rtcOccluded1M call over the
// batch (Embree 3's ray streams; Embree 4 removed them). Single: one rtcIntersect1 /
// rtcOccluded1 per ray, the portable form and the one every Embree version has.
enum class BatchCall : uint8_t { Single, Stream };

// What a replay found, so that its work cannot be skipped and can be checked.
struct ReplayCounts {
  uint64_t intersectRays = 0, hits = 0;
  uint64_t occludedRays = 0, blocked = 0;
  double shaded = 0.0;  // the sum of what a ReplayHitShader returned

  ReplayCounts& operator+=(const ReplayCounts& o);
};

// The closest hit of a replayed intersect ray: its distance along the ray, Embree's
// unnormalised geometric normal, the instance and triangle, barycentrics.
struct ReplayHit {
  float t = 0.0f;
  glm::vec3 ng{0.0f};     // in the instance's space, or in world space where 'instanced' is false
  bool instanced = true;  // false: a mesh of a one-level scene, in the top level in world space
  uint32_t instance = 0, triangle = 0;
  float b1 = 0.0f, b2 = 0.0f;
};

// Work a replay does at each hit (bench/: what the least shading costs next to traversal).
// 'index' is the ray's position in the replayed array; the return value is summed into
// ReplayCounts::shaded, so that the work cannot be optimised away. Must be thread-safe.
using ReplayHitShader = float (*)(const void* user, const RecordedRay& ray, const ReplayHit& hit,
                                  uint64_t index);

class EmbreeScene {
 public:
  // Keeps a reference to 'scene': it must outlive this object. The any-hit filter goes only
  // on meshes that need it (MASK or BLEND), unless skips.anyHitFilter is off.
  explicit EmbreeScene(const Scene& scene, const WorkSkips& skips = {});
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Closest hit in (tnear, tfar), for a ray of 'role'.
  TraceHit intersect(const glm::vec3& origin, const glm::vec3& dir, float tnear, float tfar,
                     RayRole role = RayRole::Transport) const;
  // Any hit in (tnear, tfar): a shadow ray, a transport ray.
  bool occluded(const glm::vec3& origin, const glm::vec3& dir, float tnear, float tfar) const;

  // intersect() / occluded() of every ray of a batch, through 'call', in place: each ray's
  // hit fields (ray.tfar and the ids; geomID stays ~0u where nothing was hit), or its tfar
  // set to -infinity where it is blocked. Camera rays (primary rays of a tile) also go with
  // Embree's hint that they are coherent (they start together and point alike). Recorded
  // like single calls. Thread-safe.
  void intersectBatch(BatchRayHit* rays, size_t count, BatchCall call,
                      RayRole role = RayRole::Transport) const;
  void occludedBatch(BatchRay* rays, size_t count, BatchCall call) const;

  // Instance transforms changed (not the meshes): re-commits only the top level, whose
  // LOW-quality dynamic BVH Embree refits/rebuilds in ~0.05 ms per 100 instances
  // (platform.md), instead of rebuilding any mesh BVH.
  void updateInstanceTransforms();
  // These skinned meshes' vertices moved (core/skinning.h): their BVHs are refit (built
  // with RTC_BUILD_QUALITY_REFIT); call updateInstanceTransforms() after, so the top level
  // sees their new bounds.
  void updateMeshVertices(const std::vector<int>& meshes);

  // While set, intersect() and occluded() append each ray to 'recorder' (null: off; the
  // cost when off is one predictable branch per ray). Not to be changed during a render.
  void setRecorder(RayRecorder* recorder) { recorder_ = recorder; }

  // Traces 'count' recorded rays with bare rtcIntersect1 / rtcOccluded1 calls on this
  // scene (same BVHs, same filters), with no recording and no TraceHit conversion: the
  // traversal cost alone. Thread-safe; the caller sets flush-to-zero as tracing threads do.
  // 'shader' (optional) runs at every hit of an intersect ray, with 'user'.
  ReplayCounts replay(const RecordedRay* rays, size_t count, ReplayHitShader shader = nullptr,
                      const void* user = nullptr, uint64_t firstIndex = 0) const;
  // The same on every thread: chunks of consecutive rays (one pixel's paths, then the next
  // pixel's) stay on one thread, as in the tracer's tiles, so coherence matches the render.
  ReplayCounts replayParallel(const std::vector<RecordedRay>& rays,
                              ReplayHitShader shader = nullptr, const void* user = nullptr) const;

  const EmbreeStats& stats() const { return stats_; }
  // The scene's untextured materials' inputs, computed once with its BVHs (like its
  // back-face culling, they are the materials' at construction).
  const MaterialTable& materials() const { return materials_; }
  // The bounds of everything a ray can hit, as the top-level BVH holds them (rtcGetSceneBounds:
  // no walk over the vertices); empty for an empty scene.
  Bounds bounds() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  EmbreeStats stats_;
  MaterialTable materials_;
  RayRecorder* recorder_ = nullptr;
};

// Flush-to-zero and denormals-are-zero for the calling thread (Embree's advice for speed;
// platform.md). Every tracing thread calls it once.
void enableFlushToZero();

}  // namespace photovr
