#include "trace/caustics.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "trace/sampling.h"

namespace photovr {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Whether a material can have a point where causticCaster holds: its factors allow it, or
// a texture may lower the roughness below its factor (textures multiply factors).
bool mayCast(const Material& m) {
  if (m.unlit || m.transmissionFactor != 0.0f || m.clearcoatFactor != 0.0f ||
      m.sheenColorFactor != glm::vec3(0.0f))
    return false;
  return m.roughnessFactor < kCausticCasterRoughness || m.metallicRoughnessTexture.valid();
}

// A directional light that lights anything: its irradiance and a direction to take.
bool litSun(const Light& l) {
  return l.type == Light::Type::Directional && luminance(l.color * l.intensity) > 0.0f &&
         glm::length(l.direction) > 0.0f;
}

struct MeshSphere {
  glm::vec3 centre{0.0f};
  float radius = -1.0f;  // < 0: not computed
};

MeshSphere boundingSphere(const Mesh& mesh) {
  Bounds b;
  for (const glm::vec3& p : mesh.positions) b.extend(p);
  MeshSphere s{b.center(), 0.0f};
  for (const glm::vec3& p : mesh.positions)
    s.radius = std::max(s.radius, glm::length(p - s.centre));
  return s;
}

// The largest factor by which the transform's linear part stretches a length.
float largestScale(const glm::mat4& m) {
  return std::sqrt(std::max({glm::dot(glm::vec3(m[0]), glm::vec3(m[0])),
                             glm::dot(glm::vec3(m[1]), glm::vec3(m[1])),
                             glm::dot(glm::vec3(m[2]), glm::vec3(m[2]))}));
}

// How far from 'p' along 'd' the line leaves box 'b' (slabs; negative where it left before p).
float exitDistance(const Bounds& b, const glm::vec3& p, const glm::vec3& d) {
  float t = kInfinity;
  for (int a = 0; a < 3; ++a)
    if (d[a] != 0.0f) t = std::min(t, ((d[a] > 0.0f ? b.max[a] : b.min[a]) - p[a]) / d[a]);
  return t;
}

// The eye's view of a point: its pixel and the pinhole's importance there.
struct EyeView {
  uint32_t pixel = ~0u;
  float importance = 0.0f;  // W_e = 1 / (pixel area on the film at distance 1, cos^3)
};

EyeView viewOf(const EyeCamera& cam, const glm::vec3& point) {
  const glm::vec3 local =
      glm::transpose(glm::mat3_cast(cam.pose.orientation)) * (point - cam.pose.position);
  const float depth = -local.z;
  if (!(depth > 0.0f)) return {};
  const FovTangents& f = cam.fov;
  const float spanX = f.left + f.right, spanY = f.up + f.down;
  const float px = (local.x / depth + f.left) / spanX * float(cam.width);
  const float py = (local.y / depth + f.down) / spanY * float(cam.height);
  if (!(px >= 0.0f && px < float(cam.width) && py >= 0.0f && py < float(cam.height))) return {};
  const float cosine = depth / glm::length(local);
  const float pixelArea = spanX * spanY / (float(cam.width) * float(cam.height));
  EyeView v;
  v.pixel = uint32_t(int(py)) * uint32_t(cam.width) + uint32_t(int(px));
  v.importance = 1.0f / (pixelArea * cosine * cosine * cosine);
  return v;
}

// Whether the eye's camera ray towards 'hit' meets it (and not something before it, nor
// passes through it: a back face the camera culls, a BLEND surface's coin).
bool eyeSees(const TraceContext& ctx, const glm::vec3& eye, const SurfaceHit& hit, float distance) {
  const glm::vec3 dir = (hit.position - eye) / distance;
  const TraceHit th = ctx.embree.intersect(eye, dir, 0.0f, kInfinity, RayRole::Camera);
  const float tolerance = 1e-4f * distance + 4.0f * hit.positionError;
  return th.hit && std::abs(th.t - distance) <= tolerance;
}

// The light leaving vertex 'x' along 'w' after arriving along 'in' (towards x): x's BSDF
// sampled from the light's side (u), and the factor its throughput per area of the next
// vertex takes: f(w, -in) x's shading cosine over its geometric one on the light's side, and
// its geometric cosine along w over the sample's density (r^2 cancels as at x2). False where
// the light goes no further.
bool scatterTowardsEye(const SurfaceHit& x, const glm::vec3 in, glm::vec2 u, glm::vec3& w,
                       glm::vec3& factor) {
  const Frame f = Frame::fromZ(x.shadingNormal);
  const glm::vec3 toLight = f.toLocal(-in);
  const float inGeometric = -glm::dot(in, x.geometricNormal);
  if (!(toLight.z > 0.0f && inGeometric > 0.0f)) return false;
  const BsdfSample bs = sampleBsdf(prepareBsdf(x.bsdf, toLight), u);
  if (!bs.valid() || !(bs.wi.z > 0.0f)) return false;
  w = f.toWorld(bs.wi);
  const float outGeometric = glm::dot(w, x.geometricNormal);
  if (!(outGeometric > 0.0f)) return false;
  // The BSDF as the eye's path meets it (wo on the eye's side), not the sample's reversal.
  factor = evalBsdf(x.bsdf, bs.wi, toLight) * (toLight.z / inGeometric * outGeometric / bs.pdf);
  return factor != glm::vec3(0.0f) && isFinite(factor);
}

// One light path (the numbers 'sampler' draws): the receivers it meets one after another
// after the caster, at most 'receivers' of them, into out[0 .. the count returned).
int traceLightPath(const TraceContext& ctx, const CausticSources& sources, Sampler sampler,
                   int receivers, CausticLight* out, uint32_t& rays) {
  const float uSun = sampler.next(), uCaster = sampler.next();
  const glm::vec2 uDisk = sampler.next2(), uBsdf = sampler.next2();
  const CausticSources::Start start = sources.sample(uSun, uCaster, uDisk);
  if (!(start.pdf > 0.0f)) return 0;
  // x2: what the sun's ray meets first, where the sun lights it.
  ++rays;
  const TraceHit t2 = ctx.embree.intersect(start.origin, -start.toSun, 0.0f, kInfinity);
  if (!t2.hit) return 0;
  const SurfaceHit x2 = surfaceAt(ctx.scene, t2.instance, t2.triangle, t2.b1, t2.b2, -start.toSun);
  if (!causticCaster(x2.bsdf)) return 0;
  const Frame f2 = Frame::fromZ(x2.shadingNormal);
  const glm::vec3 toSun2 = f2.toLocal(start.toSun);
  const float sunGeometric = glm::dot(start.toSun, x2.geometricNormal);
  if (!(toSun2.z > 0.0f && sunGeometric > 0.0f)) return 0;
  // Its lobe towards x1, sampled from the sun's side (the BRDF is reciprocal).
  const BsdfSample bs = sampleBsdf(prepareBsdf(x2.bsdf, toSun2), uBsdf);
  if (!bs.valid() || !(bs.wi.z > 0.0f)) return 0;
  glm::vec3 w = f2.toWorld(bs.wi);
  const float outGeometric = glm::dot(w, x2.geometricNormal);
  if (!(outGeometric > 0.0f)) return 0;
  const glm::vec3 lobe = evalBsdfLobes(x2.bsdf, toSun2, bs.wi).specular;
  if (lobe == glm::vec3(0.0f)) return 0;
  // The light's throughput leaving x2 along w, per area of x1 (r^2 cancels against x1's
  // area density): E / pdf_plane, x2's shading cosine over the geometric one at which the
  // plane's area maps onto x2's, the lobe over its density, and x2's geometric cosine
  // towards x1 (docs/ARCHITECTURE.md, "Caustics").
  glm::vec3 beta =
      start.irradiance * lobe * (toSun2.z * outGeometric / (start.pdf * sunGeometric * bs.pdf));
  glm::vec3 origin = offsetRayOrigin(x2, w);
  int reached = 0;
  for (;;) {
    // The next receiver: what the ray meets, if it is one.
    ++rays;
    const TraceHit t = ctx.embree.intersect(origin, w, 0.0f, kInfinity);
    if (!t.hit) break;
    const SurfaceHit x = surfaceAt(ctx.scene, t.instance, t.triangle, t.b1, t.b2, w);
    if (!causticReceiver(x.bsdf)) break;
    out[reached++] = {{t.instance, t.triangle, t.b1, t.b2}, w, beta};
    glm::vec3 factor;
    if (reached == receivers || !scatterTowardsEye(x, w, sampler.next2(), w, factor)) break;
    beta *= factor;
    origin = offsetRayOrigin(x, w);
  }
  return reached;
}

// A light path that reached x1, connected to the eye of 'cam'.
CausticSplat connectToEye(const TraceContext& ctx, const CausticLight& light, const EyeCamera& cam,
                          uint32_t& rays) {
  const glm::vec3 w = light.w;
  const SurfaceHit x1 =
      surfaceAt(ctx.scene, light.x1.instance, light.x1.triangle, light.x1.b1, light.x1.b2, w);
  const glm::vec3 toEye = cam.pose.position - x1.position;
  const float distance = glm::length(toEye);
  if (!(distance > 0.0f)) return {};
  const glm::vec3 e = toEye / distance;
  const float eyeGeometric = glm::dot(e, x1.geometricNormal);
  if (!(eyeGeometric > 0.0f)) return {};  // the eye on x2's side of it
  const EyeView view = viewOf(cam, x1.position);
  if (view.pixel == ~0u) return {};
  const Frame f1 = Frame::fromZ(x1.shadingNormal);
  const glm::vec3 wo1 = f1.toLocal(e), wi1 = f1.toLocal(-w);
  if (!(wo1.z > 0.0f && wi1.z > 0.0f)) return {};
  const BsdfLobes f = evalBsdfLobes(x1.bsdf, wo1, wi1);
  if (f.total() == glm::vec3(0.0f)) return {};
  ++rays;
  if (!eyeSees(ctx, cam.pose.position, x1, distance)) return {};
  // x1's shading cosine over its geometric one towards x2 (the area density's), then the
  // connection's geometric term and the eye's importance.
  const float inGeometric = -glm::dot(w, x1.geometricNormal);
  const float scale = wi1.z / inGeometric * eyeGeometric / (distance * distance) * view.importance;
  CausticSplat s;
  s.pixel = view.pixel;
  s.diffuse = light.beta * f.diffuse * scale;
  s.specular = light.beta * f.specular * scale;
  if (!isFinite(s.diffuse) || !isFinite(s.specular)) return {};
  return s;
}

// This frame's light paths into 'paths': path k's receivers in its slots
// k x kCausticReceivers + r, reached[slot] where the path reached that one.
void traceLightPaths(const TraceContext& ctx, const CausticSources& sources, uint32_t frame,
                     uint32_t pathCount, CausticPaths& paths, uint64_t* rays) {
  const size_t slots = size_t(pathCount) * kCausticReceivers;
  paths.lights.resize(slots);
  paths.reached.assign(slots, 0);
  if (sources.empty()) return;
  // A path's r-th receiver is reached after r bounces from the eye's side: no more than the
  // path tracer takes (--bounces), which would otherwise leave them out.
  const int receivers = std::min(kCausticReceivers, ctx.settings.maxBounces);
  // One Owen-scrambled Sobol sequence over every light path of every frame, keyed by the
  // seed alone (not the eye: both eyes take the same paths, so their noise agrees).
  const uint32_t key = hashCombine(ctx.settings.seed, 0x43415553u);  // "CAUS"
  std::atomic<uint64_t> traced{0};
  tbb::parallel_for(
      tbb::blocked_range<uint32_t>(0, pathCount, 256), [&](const tbb::blocked_range<uint32_t>& r) {
        enableFlushToZero();
        uint32_t local = 0;
        for (uint32_t k = r.begin(); k < r.end(); ++k) {
          // The index over every frame's paths, in 64 bits: its high word
          // names the sequence, so that a long run does not wrap around.
          const uint64_t index = uint64_t(frame) * pathCount + k;
          const uint32_t seq = hashCombine(key, uint32_t(index >> 32));
          const Sampler sampler{seq, 0, pcgHash(seq), uint32_t(index), SamplerKind::Sobol};
          const size_t first = size_t(k) * kCausticReceivers;
          const int n =
              traceLightPath(ctx, sources, sampler, receivers, &paths.lights[first], local);
          for (int r = 0; r < n; ++r) paths.reached[first + size_t(r)] = 1;
        }
        traced += local;
      });
  if (rays) *rays += traced;
}

std::vector<CausticSplat> connectToEye(const TraceContext& ctx, const CausticPaths& paths,
                                       const EyeCamera& camera, uint64_t* rays) {
  const size_t n = paths.lights.size();
  std::vector<CausticSplat> splats(n);
  std::atomic<uint64_t> traced{0};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 256),
                    [&](const tbb::blocked_range<size_t>& r) {
                      enableFlushToZero();
                      uint32_t local = 0;
                      for (size_t k = r.begin(); k < r.end(); ++k)
                        if (paths.reached[k])
                          splats[k] = connectToEye(ctx, paths.lights[k], camera, local);
                      traced += local;
                    });
  if (rays) *rays += traced;
  return splats;
}

}  // namespace

bool causticCaster(const BsdfParams& b) {
  return b.transmission == 0.0f && b.clearcoat == 0.0f && b.sheenColor == glm::vec3(0.0f) &&
         b.roughness < kCausticCasterRoughness;
}

bool causticReceiver(const BsdfParams& b) {
  return b.transmission == 0.0f && b.roughness >= kCausticReceiverRoughness &&
         (b.clearcoat == 0.0f || b.clearcoatRoughness >= kCausticReceiverRoughness);
}

bool hasLightTracedCaustics(const Scene& scene) {
  if (std::none_of(scene.lights.begin(), scene.lights.end(), litSun)) return false;
  return std::any_of(scene.instances.begin(), scene.instances.end(), [&](const Instance& i) {
    return scene.hasMesh(i.mesh) && mayCast(scene.materials[scene.meshes[i.mesh].material]);
  });
}

uint32_t causticPathCount(int width, int height, int samplesPerPixel) {
  const uint64_t samples = uint64_t(std::max(width, 0)) * uint64_t(std::max(height, 0)) *
                           uint64_t(std::max(samplesPerPixel, 1));
  return uint32_t(
      std::min<uint64_t>((samples + kCausticSamplesPerPath - 1) / kCausticSamplesPerPath,
                         uint64_t(1) << 22));  // 4 M paths, 160 MB
}

CausticSources::CausticSources(const Scene& scene, const Bounds& world) {
  float power = 0.0f;
  for (const Light& l : scene.lights) {
    if (!litSun(l)) continue;
    const glm::vec3 e = l.color * l.intensity;
    suns_.push_back({-glm::normalize(l.direction), e, luminance(e)});
    power += luminance(e);
  }
  for (Sun& s : suns_) s.probability /= power;
  if (suns_.empty()) return;
  std::vector<MeshSphere> spheres(scene.meshes.size());
  world_ = world;
  // Past the box by more than the rounding of the start's point (its coordinates' size).
  const glm::vec3 reach = glm::max(glm::abs(world.min), glm::abs(world.max));
  worldMargin_ = 1e-5f * (glm::length(world.extent()) + glm::length(reach));
  for (const Instance& inst : scene.instances) {
    if (!scene.hasMesh(inst.mesh)) continue;
    const Mesh& mesh = scene.meshes[inst.mesh];
    if (mesh.positions.empty() || !mayCast(scene.materials[mesh.material])) continue;
    MeshSphere& s = spheres[inst.mesh];
    if (s.radius < 0.0f) s = boundingSphere(mesh);
    // Grown by a part in 1e5 against the rounding of the transform and of the start's point.
    const float radius = s.radius * largestScale(inst.transform) * (1.0f + 1e-5f);
    if (!(radius > 0.0f)) continue;
    casters_.push_back({glm::vec3(inst.transform * glm::vec4(s.centre, 1.0f)), radius});
  }
  float total = 0.0f;
  for (const Caster& c : casters_) casterCdf_.push_back(total += c.radius * c.radius);
  for (float& c : casterCdf_) c /= total;
  diskArea_ = kPi * total;
}

CausticSources::Start CausticSources::sample(float uSun, float uCaster, glm::vec2 uDisk) const {
  Start s;
  if (empty()) return s;
  size_t sun = 0;
  for (float acc = suns_[0].probability; sun + 1 < suns_.size() && uSun >= acc;)
    acc += suns_[++sun].probability;
  const size_t caster = std::min<size_t>(
      std::upper_bound(casterCdf_.begin(), casterCdf_.end(), uCaster) - casterCdf_.begin(),
      casters_.size() - 1);
  const Sun& light = suns_[sun];
  const Caster& c = casters_[caster];
  const Frame plane = Frame::fromZ(light.toSun);
  const glm::vec2 d = sampleUniformDiskConcentric(uDisk) * c.radius;
  const glm::vec3 point = c.centre + d.x * plane.x + d.y * plane.y;
  // The density of the point: every caster's disk that holds it could have drawn it.
  uint32_t covering = 0;
  for (const Caster& o : casters_) {
    const glm::vec3 v = point - o.centre;
    const float along = glm::dot(v, light.toSun);
    covering += glm::dot(v, v) - along * along <= o.radius * o.radius;
  }
  covering = std::max(covering, 1u);  // the drawn disk holds it, up to rounding
  s.toSun = light.toSun;
  s.irradiance = light.irradiance;
  s.pdf = light.probability * float(covering) / diskArea_;
  // Beyond everything the sun's ray could meet before the point: where its line leaves the
  // BVH's box, not farther, for x2's precision (the ray's t and barycentrics lose digits with
  // the distance: from the bounding sphere of spheres' 200 m ground, 1e-3 of a triangle).
  const float ahead = std::max(exitDistance(world_, point, light.toSun), 0.0f);
  s.origin = point + light.toSun * (ahead + worldMargin_);
  return s;
}

std::vector<CausticSplat> traceCaustics(const TraceContext& ctx, const CausticSources& sources,
                                        const EyeCamera& camera, uint32_t frame, uint32_t pathCount,
                                        uint64_t* rays) {
  CausticPaths paths;
  traceLightPaths(ctx, sources, frame, pathCount, paths, rays);
  return connectToEye(ctx, paths, camera, rays);
}

void addCaustics(EyeImage& image, std::span<const CausticSplat> splats, uint32_t pathCount) {
  if (splats.empty() || pathCount == 0) return;
  const float share = 1.0f / float(pathCount);
  const bool lobes = !image.diffuse.empty();
  for (const CausticSplat& s : splats) {
    if (s.pixel >= image.color.size() || image.samples[s.pixel] == 0) continue;
    const glm::vec3 d = s.diffuse * share, sp = s.specular * share;
    image.color[s.pixel] += d + sp;
    if (!lobes) continue;
    image.diffuse[s.pixel] += d / image.diffuseAlbedo[s.pixel];
    image.specular[s.pixel] += sp / image.specularAlbedo[s.pixel];
  }
}

void traceCausticsInto(const TraceContext& ctx, const EyeCamera& camera, uint32_t frame,
                       EyeImage& image, CausticPaths* shared) {
  // Their paths have a second vertex, which --bounces 0 does not reach.
  if (!ctx.settings.caustics || ctx.settings.maxBounces < 1) return;
  const auto start = std::chrono::steady_clock::now();
  const uint32_t count =
      causticPathCount(camera.width, camera.height, ctx.settings.samplesPerPixel);
  CausticPaths own;
  CausticPaths& paths = shared ? *shared : own;
  if (!paths.holds(ctx, frame, count)) {
    traceLightPaths(ctx, CausticSources(ctx.scene, ctx.embree.bounds()), frame, count, paths,
                    &image.rays);
    paths.key = {&ctx.scene, &ctx.embree, ctx.settings.seed, frame, count};
  }
  const std::vector<CausticSplat> splats = connectToEye(ctx, paths, camera, &image.rays);
  addCaustics(image, splats, count);
  image.causticSplats = uint64_t(std::count_if(
      splats.begin(), splats.end(), [](const CausticSplat& s) { return s.pixel != ~0u; }));
  image.causticMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

bool CausticPaths::holds(const TraceContext& ctx, uint32_t frame, uint32_t count) const {
  return key.scene == &ctx.scene && key.embree == &ctx.embree && key.seed == ctx.settings.seed &&
         key.frame == frame && key.count == count &&
         lights.size() == size_t(count) * kCausticReceivers;
}

}  // namespace photovr
