#include "trace/embree_scene.h"

#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_reduce.h>
#include <xmmintrin.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/bvh_layout.h"
#include "trace/rng.h"
#include "trace/surface.h"
#include "trace/texture_sampling.h"

namespace photovr {
namespace {

// Meshes up to this many triangles get MEDIUM quality BVHs: on this hardware MEDIUM traces
// as fast as HIGH and builds 5x faster (platform.md: 1M triangles, 150 vs 800 ms). Larger
// ones fall back to LOW (58 ms per 1M) so loading stays interactive.
constexpr size_t kMediumQualityLimit = 4'000'000;

void embreeError(void*, RTCError code, const char* message) {
  // One Embree error callback (STYLE.md 12): Embree errors are broken invariants here,
  // never user input (the loader validated it), so they stop the program loudly.
  std::fprintf(stderr, "photovr: Embree error %d: %s\n", int(code), message ? message : "");
}

// What the any-hit filter needs: the mesh's data and which tests apply.
struct FilterData {
  const Scene* scene = nullptr;
  const Mesh* mesh = nullptr;
  const Material* material = nullptr;
  bool alphaMask = false;      // MASK material: reject hits below the alpha cutoff
  bool alphaBlend = false;     // BLEND material: accept hits with probability alpha
  bool cullBackFaces = false;  // single-sided material: back faces are invisible (glTF 3.9.5)
  // Its triangles are in the top level in world space, mirrored by their instance's
  // transform: the world winding is the reverse of the front's.
  bool flipped = false;
};

// The instance a hit belongs to: Embree's instance id, or, for a mesh put in the top level
// in world space (one instance alone uses it), the geometry id, which is the instance's.
uint32_t instanceOfHit(uint32_t instID, uint32_t geomID) {
  return instID != RTC_INVALID_GEOMETRY_ID ? instID : geomID;
}

float maskAlpha(const FilterData& d, uint32_t triangle, float u, float v) {
  return surfaceAlpha(*d.scene, *d.mesh, *d.material, triangle, u, v);
}

uint32_t floatBits(float f) {
  uint32_t b;
  std::memcpy(&b, &f, sizeof b);
  return b;
}

// alpha BLEND's coin for one ray and candidate triangle: a hash of the ray (its origin and
// direction, different for every sample, bounce and frame, and the same at any thread
// count) and of the triangle, so each layer a ray passes is an independent coin.
float coverageNumber(const RTCFilterFunctionNArguments* args, unsigned i, uint32_t prim) {
  const unsigned n = args->N;
  uint32_t h = pcgHash(floatBits(RTCRayN_org_x(args->ray, n, i)));
  for (float f : {RTCRayN_org_y(args->ray, n, i), RTCRayN_org_z(args->ray, n, i),
                  RTCRayN_dir_x(args->ray, n, i), RTCRayN_dir_y(args->ray, n, i),
                  RTCRayN_dir_z(args->ray, n, i)})
    h = hashCombine(h, floatBits(f));
  const uint32_t instance =
      instanceOfHit(RTCHitN_instID(args->hit, n, i, 0), RTCHitN_geomID(args->hit, n, i));
  h = hashCombine(hashCombine(h, instance), prim);
  return toUnitFloat(h);
}

// Any-hit filter of MASK and BLEND meshes: the tracer sees what the G-buffer sees — MASK
// texels below the cutoff are holes (the shader's discard), a BLEND surface is met with
// probability alpha.
void alphaFilter(const RTCFilterFunctionNArguments* args) {
  const auto* d = static_cast<const FilterData*>(args->geometryUserPtr);
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] == 0) continue;
    const uint32_t prim = RTCHitN_primID(args->hit, n, i);
    const float u = RTCHitN_u(args->hit, n, i), v = RTCHitN_v(args->hit, n, i);
    if (d->alphaMask && maskAlpha(*d, prim, u, v) < d->material->alphaCutoff) args->valid[i] = 0;
    if (d->alphaBlend && coverageNumber(args, i, prim) >= maskAlpha(*d, prim, u, v))
      args->valid[i] = 0;
  }
}

// Camera rays' filter (in their intersect context; Embree runs it after a mesh's own):
// single-sided back faces are culled, as the rasterizer culls them. A back face is one the
// ray meets from behind the counter-clockwise winding, in object space: Embree hands
// instanced geometry's filters the ray and the hit's unnormalised geometric normal
// (counter-clockwise front, Embree's RTC_GEOMETRY_TYPE_TRIANGLE convention) in the
// instance's space, where a mirroring instance transform cannot flip the answer; a mesh in
// the top level is in world space, where its 'flipped' says so. Using Embree's Ng instead of
// recomputing the normal from the mesh saves six indexed loads and a cross product per
// candidate hit.
void cameraCullFilter(const RTCFilterFunctionNArguments* args) {
  const auto* d = static_cast<const FilterData*>(args->geometryUserPtr);
  if (!d->cullBackFaces) return;
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    const float facing = RTCRayN_dir_x(args->ray, n, i) * RTCHitN_Ng_x(args->hit, n, i) +
                         RTCRayN_dir_y(args->ray, n, i) * RTCHitN_Ng_y(args->hit, n, i) +
                         RTCRayN_dir_z(args->ray, n, i) * RTCHitN_Ng_z(args->hit, n, i);
    if ((facing > 0.0f) != d->flipped && facing != 0.0f) args->valid[i] = 0;
  }
}

}  // namespace

struct EmbreeScene::Impl {
  const Scene& scene;
  RTCDevice device = nullptr;
  RTCScene top = nullptr;
  std::vector<RTCScene> meshScenes;  // null for a mesh in the top level
  // Per instance: its instance geometry, or its mesh's triangles in the top level.
  std::vector<RTCGeometry> instanceGeometries;
  std::vector<bool> inTopLevel;
  // Per triangle geometry (a mesh's, or an instance's copy of it in the top level); reserved for
  // all of them up front, as Embree keeps pointers to them.
  std::vector<FilterData> filterData;
  std::vector<uint8_t> meshFiltered;  // per mesh: counted in EmbreeStats::filteredMeshes
  bool cameraCulling = false;  // some mesh is single-sided: camera rays carry cameraCullFilter
  bool filterAlways = false;   // skips.anyHitFilter off: the alpha filter on every mesh

  explicit Impl(const Scene& s) : scene(s) {}
  ~Impl() {
    if (top) rtcReleaseScene(top);
    for (RTCScene m : meshScenes)
      if (m) rtcReleaseScene(m);
    if (device) rtcReleaseDevice(device);
  }
  RTCGeometry triangles(size_t mesh, const glm::mat4* toWorld, EmbreeStats& stats);
  RTCScene buildMesh(size_t index, EmbreeStats& stats);
  void buildInstances(EmbreeStats& stats);
};

// The world-space copy of a mesh's vertices under 'toWorld'.
void writeWorldVertices(glm::vec3* out, const Mesh& mesh, const glm::mat4& toWorld) {
  for (size_t i = 0; i < mesh.vertexCount(); ++i)
    out[i] = glm::vec3(toWorld * glm::vec4(mesh.positions[i], 1.0f));
}

// A mesh's triangle geometry with its filter data: in object space, or in world space under
// 'toWorld' (a mesh in the top level).
RTCGeometry EmbreeScene::Impl::triangles(size_t index, const glm::mat4* toWorld,
                                         EmbreeStats& stats) {
  const Mesh& mesh = scene.meshes[index];
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<glm::vec3*>(rtcSetNewGeometryBuffer(
      g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(glm::vec3), mesh.vertexCount()));
  if (toWorld)
    writeWorldVertices(v, mesh, *toWorld);
  else
    std::copy(mesh.positions.begin(), mesh.positions.end(), v);
  auto* i = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
      g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), mesh.triangleCount()));
  std::copy(mesh.indices.begin(), mesh.indices.end(), i);
  const Material& mat = scene.materials[mesh.material];
  FilterData& d = filterData.emplace_back();
  d = {&scene,
       &mesh,
       &mat,
       mat.alphaMode == AlphaMode::Mask,
       mat.alphaMode == AlphaMode::Blend,
       mat.cullsBackFaces(),
       toWorld && glm::determinant(glm::mat3(*toWorld)) < 0.0f};
  rtcSetGeometryUserData(g, &d);  // what either filter reads
  if (d.alphaMask || d.alphaBlend || filterAlways) {
    stats.filteredMeshes += !meshFiltered[index];
    meshFiltered[index] = 1;
    rtcSetGeometryIntersectFilterFunction(g, alphaFilter);
    rtcSetGeometryOccludedFilterFunction(g, alphaFilter);
    stats.alphaFilter |= d.alphaMask || d.alphaBlend;
  }
  return g;
}

RTCScene EmbreeScene::Impl::buildMesh(size_t index, EmbreeStats& stats) {
  const Mesh& mesh = scene.meshes[index];
  RTCScene s = rtcNewScene(device);
  rtcSetSceneBuildQuality(s, mesh.triangleCount() <= kMediumQualityLimit ? RTC_BUILD_QUALITY_MEDIUM
                                                                         : RTC_BUILD_QUALITY_LOW);
  RTCGeometry g = triangles(index, nullptr, stats);
  if (mesh.skinned()) {
    // Its vertices move every pose: the BVH is refit, not rebuilt. Embree honours a
    // geometry's REFIT quality only in a scene of LOW build quality (rtcSetGeometryBuildQuality
    // (3): "uses the per-geometry build quality when the scene build quality is set to
    // RTC_BUILD_QUALITY_LOW"); under MEDIUM a 131k-triangle grid was rebuilt, 25 ms a pose.
    rtcSetSceneFlags(s, RTC_SCENE_FLAG_DYNAMIC);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_LOW);
    rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_REFIT);
  }
  // Embree runs a context's filter on a scene's hits only where the scene (each instanced one
  // too) enables it.
  if (cameraCulling)
    rtcSetSceneFlags(s,
                     RTCSceneFlags(rtcGetSceneFlags(s) | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION));
  rtcCommitGeometry(g);
  rtcAttachGeometryByID(s, g, 0);
  rtcReleaseGeometry(g);
  rtcCommitScene(s);
  return s;
}

// Two levels, instances of mesh BVHs; or one, every instance's mesh copied into the top level
// in world space, where the copies are cheap (core/bvh_layout.h): a ray then pays no instance
// transform and no second traversal (cornell's and spheres' rays traced 12-16 % faster so,
// docs/MEASUREMENTS.md "One BVH level where no mesh is shared"; spheres with meshes shared by
// 2-10 instances 3-6 %, "Shared meshes copied"). The copies cost memory and build time (a
// tenfold copy built 18-28x slower), so a scene whose meshes are shared more than
// kOneLevelCopies-fold keeps two levels, as do heavily instanced scenes whose small shared
// meshes trace faster instanced (atrium flattened, 41-fold: 7 % slower). Not both in one
// scene: Embree keeps a BVH per primitive type, so a ray would traverse an instance BVH and a
// triangle BVH (atrium, with its floor alone in the top level, traced 4-8 % slower; spheres'
// meshes used once in a BVH of their own, instanced once beside shared ones, 5 % slower than
// two levels). A scene whose instances move (an animation) keeps two levels: moving a
// top-level mesh rewrites its vertices and rebuilds the top level.
void EmbreeScene::Impl::buildInstances(EmbreeStats& stats) {
  top = rtcNewScene(device);
  const bool anyInTop = std::find(inTopLevel.begin(), inTopLevel.end(), true) != inTopLevel.end();
  // The top level changes when instances move: LOW quality + DYNAMIC makes re-commits
  // cheap. With the meshes in it (a still scene), MEDIUM, as a mesh's own BVH.
  rtcSetSceneFlags(top,
                   RTCSceneFlags((anyInTop ? 0 : RTC_SCENE_FLAG_DYNAMIC) |
                                 (cameraCulling ? RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION : 0)));
  rtcSetSceneBuildQuality(top, anyInTop ? RTC_BUILD_QUALITY_MEDIUM : RTC_BUILD_QUALITY_LOW);
  for (size_t k = 0; k < scene.instances.size(); ++k) {
    const Instance& inst = scene.instances[k];
    RTCGeometry g = nullptr;
    if (inTopLevel[k]) {
      g = triangles(size_t(inst.mesh), &inst.transform, stats);
    } else {
      g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
      rtcSetGeometryInstancedScene(g, meshScenes[size_t(inst.mesh)]);
      rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &inst.transform[0][0]);
    }
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(top, g, unsigned(k));  // geometry id == Scene instance index
    instanceGeometries.push_back(g);
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(top);
}

EmbreeScene::EmbreeScene(const Scene& scene, const WorkSkips& skips)
    : impl_(std::make_unique<Impl>(scene)), materials_(scene) {
  const auto t0 = std::chrono::steady_clock::now();
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw std::runtime_error("Embree: cannot create a device");
  rtcSetDeviceErrorFunction(impl_->device, embreeError, nullptr);
  impl_->filterData.reserve(scene.meshes.size() + scene.instances.size());
  impl_->meshFiltered.assign(scene.meshes.size(), 0);
  for (const Mesh& mesh : scene.meshes)
    impl_->cameraCulling |= scene.materials[size_t(mesh.material)].cullsBackFaces();
  stats_.cameraBackFaceCulling = impl_->cameraCulling;
  impl_->filterAlways = !skips.anyHitFilter;
  // One level where the scene does not move, no mesh is skinned and the shared meshes' copies
  // are cheap (core/bvh_layout.h, buildInstances).
  const bool oneLevel = bvhLayoutOf(scene).oneLevel;
  impl_->inTopLevel.assign(scene.instances.size(), oneLevel);
  stats_.instancesInTopLevel = oneLevel ? scene.instances.size() : 0;
  std::vector<uint8_t> used(scene.meshes.size(), 0);
  for (const Instance& inst : scene.instances) used[size_t(inst.mesh)] = 1;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const bool inTop = oneLevel && used[m];
    impl_->meshScenes.push_back(inTop ? nullptr : impl_->buildMesh(m, stats_));
    stats_.meshBvhs += !inTop;
  }
  impl_->buildInstances(stats_);
  stats_.instances = scene.instances.size();
  stats_.buildQuality =
      oneLevel ? "one level: every instance's mesh in world space, MEDIUM"
               : "meshes MEDIUM (LOW above 4M triangles; skinned: LOW, refit), top level LOW "
                 "dynamic";
  stats_.buildMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

EmbreeScene::~EmbreeScene() = default;

static RTCRayHit makeRayHit(const glm::vec3& o, const glm::vec3& d, float tnear, float tfar) {
  RTCRayHit rh{};
  rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
  rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
  rh.ray.tnear = tnear;
  rh.ray.tfar = tfar;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

namespace {

TraceHit traceHitOf(const RTCRayHit& rh) {
  TraceHit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  h.hit = true;
  h.t = rh.ray.tfar;
  h.instance = instanceOfHit(rh.hit.instID[0], rh.hit.geomID);
  h.triangle = rh.hit.primID;
  h.b1 = rh.hit.u;
  h.b2 = rh.hit.v;
  return h;
}

static_assert(sizeof(BatchRay) == sizeof(RTCRay) && alignof(BatchRay) == alignof(RTCRay));
static_assert(offsetof(BatchRay, tfar) == offsetof(RTCRay, tfar) &&
              offsetof(BatchRay, flags) == offsetof(RTCRay, flags));
static_assert(sizeof(BatchRayHit) == sizeof(RTCRayHit) &&
              offsetof(BatchRayHit, ng) == offsetof(RTCRayHit, hit.Ng_x) &&
              offsetof(BatchRayHit, primID) == offsetof(RTCRayHit, hit.primID) &&
              offsetof(BatchRayHit, instID) == offsetof(RTCRayHit, hit.instID));
static_assert(RTC_MAX_INSTANCE_LEVEL_COUNT == 1 && RTC_INVALID_GEOMETRY_ID == ~0u);

void record(RayRecorder& recorder, const BatchRay& r, RecordedRay::Kind kind) {
  recorder.record({r.origin, r.tnear, r.dir, r.tfar, kind});
}

RTCRay* embreeRays(BatchRay* rays) {
  return reinterpret_cast<RTCRay*>(rays);
}
RTCRayHit* embreeRays(BatchRayHit* rays) {
  return reinterpret_cast<RTCRayHit*>(rays);
}

RecordedRay::Kind intersectKind(RayRole role) {
  return role == RayRole::Camera ? RecordedRay::Kind::Camera : RecordedRay::Kind::Intersect;
}

// A query's context: camera rays cull single-sided back faces ('culling': the scene has
// some) and, in a batch ('batch'), are hinted coherent.
void initContext(RTCIntersectContext& ctx, RayRole role, bool culling, bool batch) {
  rtcInitIntersectContext(&ctx);
  if (role == RayRole::Camera && culling) ctx.filter = cameraCullFilter;
  if (!batch) return;
  ctx.flags = role == RayRole::Camera ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT
                                      : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
}

}  // namespace

TraceHit EmbreeScene::intersect(const glm::vec3& o, const glm::vec3& d, float tnear, float tfar,
                                RayRole role) const {
  if (recorder_) recorder_->record({o, tnear, d, tfar, intersectKind(role)});
  RTCIntersectContext ctx;
  initContext(ctx, role, impl_->cameraCulling, false);
  RTCRayHit rh = makeRayHit(o, d, tnear, tfar);
  rtcIntersect1(impl_->top, &ctx, &rh);
  return traceHitOf(rh);
}

bool EmbreeScene::occluded(const glm::vec3& o, const glm::vec3& d, float tnear, float tfar) const {
  if (recorder_) recorder_->record({o, tnear, d, tfar, RecordedRay::Kind::Occluded});
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay ray = makeRayHit(o, d, tnear, tfar).ray;
  rtcOccluded1(impl_->top, &ctx, &ray);
  return ray.tfar == -std::numeric_limits<float>::infinity();
}

void EmbreeScene::intersectBatch(BatchRayHit* rays, size_t count, BatchCall call,
                                 RayRole role) const {
  for (size_t i = 0; recorder_ && i < count; ++i)
    record(*recorder_, rays[i].ray, intersectKind(role));
  RTCIntersectContext ctx;
  initContext(ctx, role, impl_->cameraCulling, true);
  if (call == BatchCall::Single) {
    for (size_t i = 0; i < count; ++i) rtcIntersect1(impl_->top, &ctx, embreeRays(rays + i));
    return;
  }
  rtcIntersect1M(impl_->top, &ctx, embreeRays(rays), unsigned(count), sizeof(BatchRayHit));
}

void EmbreeScene::occludedBatch(BatchRay* rays, size_t count, BatchCall call) const {
  for (size_t i = 0; recorder_ && i < count; ++i)
    record(*recorder_, rays[i], RecordedRay::Kind::Occluded);
  RTCIntersectContext ctx;
  initContext(ctx, RayRole::Transport, false, true);
  if (call == BatchCall::Single) {
    for (size_t i = 0; i < count; ++i) rtcOccluded1(impl_->top, &ctx, embreeRays(rays + i));
    return;
  }
  rtcOccluded1M(impl_->top, &ctx, embreeRays(rays), unsigned(count), sizeof(BatchRay));
}

ReplayCounts& ReplayCounts::operator+=(const ReplayCounts& o) {
  intersectRays += o.intersectRays, hits += o.hits;
  occludedRays += o.occludedRays, blocked += o.blocked;
  shaded += o.shaded;
  return *this;
}

namespace {

ReplayHit replayHitOf(const RTCRayHit& rh) {
  ReplayHit h;
  h.t = rh.ray.tfar;
  h.ng = glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
  h.instanced = rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID;
  h.instance = instanceOfHit(rh.hit.instID[0], rh.hit.geomID);
  h.triangle = rh.hit.primID;
  h.b1 = rh.hit.u;
  h.b2 = rh.hit.v;
  return h;
}

}  // namespace

ReplayCounts EmbreeScene::replay(const RecordedRay* rays, size_t count, ReplayHitShader shader,
                                 const void* user, uint64_t firstIndex) const {
  RTCIntersectContext transport, camera;
  initContext(transport, RayRole::Transport, false, false);
  initContext(camera, RayRole::Camera, impl_->cameraCulling, false);
  ReplayCounts c;
  for (size_t i = 0; i < count; ++i) {
    const RecordedRay& r = rays[i];
    RTCRayHit rh = makeRayHit(r.origin, r.dir, r.tnear, r.tfar);
    if (r.kind != RecordedRay::Kind::Occluded) {
      rtcIntersect1(impl_->top, r.kind == RecordedRay::Kind::Camera ? &camera : &transport, &rh);
      ++c.intersectRays;
      if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
      ++c.hits;
      if (!shader) continue;
      c.shaded += shader(user, r, replayHitOf(rh), firstIndex + i);
    } else {
      rtcOccluded1(impl_->top, &transport, &rh.ray);
      ++c.occludedRays;
      c.blocked += rh.ray.tfar == -std::numeric_limits<float>::infinity();
    }
  }
  return c;
}

struct RayRecorder::Impl {
  tbb::enumerable_thread_specific<std::vector<RecordedRay>> perThread;
};

RayRecorder::RayRecorder() : impl_(std::make_unique<Impl>()) {}
RayRecorder::~RayRecorder() = default;

void RayRecorder::record(const RecordedRay& ray) {
  impl_->perThread.local().push_back(ray);
}

std::vector<RecordedRay> RayRecorder::take() {
  std::vector<RecordedRay> all;
  for (std::vector<RecordedRay>& v : impl_->perThread) {
    all.insert(all.end(), v.begin(), v.end());
    v.clear();
  }
  return all;
}

void EmbreeScene::updateInstanceTransforms() {
  for (size_t k = 0; k < impl_->instanceGeometries.size(); ++k) {
    RTCGeometry g = impl_->instanceGeometries[k];
    const Instance& inst = impl_->scene.instances[k];
    if (impl_->inTopLevel[k]) {  // a still scene's: only a caller that moved it comes here
      auto* v = static_cast<glm::vec3*>(rtcGetGeometryBufferData(g, RTC_BUFFER_TYPE_VERTEX, 0));
      writeWorldVertices(v, impl_->scene.meshes[size_t(inst.mesh)], inst.transform);
      rtcUpdateGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0);
    } else {
      rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &inst.transform[0][0]);
    }
    rtcCommitGeometry(g);
  }
  rtcCommitScene(impl_->top);
}

void EmbreeScene::updateMeshVertices(const std::vector<int>& meshes) {
  for (int m : meshes) {
    const Mesh& mesh = impl_->scene.meshes[size_t(m)];
    RTCScene s = impl_->meshScenes[size_t(m)];
    RTCGeometry g = rtcGetGeometry(s, 0);
    auto* v = static_cast<glm::vec3*>(rtcGetGeometryBufferData(g, RTC_BUFFER_TYPE_VERTEX, 0));
    std::copy(mesh.positions.begin(), mesh.positions.end(), v);
    rtcUpdateGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(g);
    rtcCommitScene(s);
  }
}

ReplayCounts EmbreeScene::replayParallel(const std::vector<RecordedRay>& rays,
                                         ReplayHitShader shader, const void* user) const {
  constexpr size_t kChunk = 4096;  // ~ the rays of one 16 x 16 tile at 4 spp in cornell
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, rays.size(), kChunk), ReplayCounts{},
      [&](const tbb::blocked_range<size_t>& r, ReplayCounts total) {
        enableFlushToZero();
        return total += replay(rays.data() + r.begin(), r.size(), shader, user, r.begin());
      },
      [](ReplayCounts a, const ReplayCounts& b) { return a += b; });
}

Bounds EmbreeScene::bounds() const {
  RTCBounds b;
  rtcGetSceneBounds(impl_->top, &b);
  Bounds out;
  if (!(b.lower_x <= b.upper_x)) return out;
  out.extend({b.lower_x, b.lower_y, b.lower_z});
  out.extend({b.upper_x, b.upper_y, b.upper_z});
  return out;
}

void enableFlushToZero() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

}  // namespace photovr
