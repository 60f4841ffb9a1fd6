// Caustics of directional lights by light tracing: the paths eye - x1 - x2 - sun whose x2
// reflects the sun in a smooth specular lobe (a mirror-like sphere throwing the sun onto
// the floor). A path tracer finds them only where x1's bounce happens to land in x2's
// narrow highlight, and then with the weight of that highlight (GGX's peak 1 / (pi alpha^2)
// is ~8e4 at the floor alpha): rare, huge samples, an error that falls as N^-0.65 on the
// spheres scene (docs/MEASUREMENTS.md). Traced from the sun instead (Veach 1997, ch. 10:
// the light-tracing strategy of bidirectional path tracing, t = 1), each such path is a
// ray from the sun to x2, a sample of x2's lobe towards x1, and a connection from x1 to
// the eye: the sun's image in the mirror spreads over the receivers as it should. The
// light goes on from x1 to the receivers x1 lights (eye - x0 - x1 - x2 - sun), up to
// kCausticReceivers of them, each connected to the eye.
//
// The two tracers split the paths between them, with no MIS weights (a partition, each
// path estimated by exactly one of them): light tracing takes the specular lobe of x2 for
// paths whose vertices from the eye up to x2 are 1 .. kCausticReceivers causticReceivers and
// whose x2 is a causticCaster lit by a directional light; next-event estimation at the path
// tracer's vertex x2 leaves out that lobe for those paths (path_tracer.cpp, directLight),
// and keeps everything else. Both tests read only the vertex's BSDF inputs, so both tracers
// decide every path alike. The derivation: docs/ARCHITECTURE.md, "Caustics".
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "trace/hit_geometry.h"
#include "trace/path_tracer.h"

namespace photovr {

// Perceptual roughness below which a plain BRDF's specular lobe is the light tracer's at
// x2 (alpha 0.09: D's peak 39 against a Lambert lobe's 1 / pi; the throw-away build of
// docs/MEASUREMENTS.md that left out NEE to the sun from such vertices reached by a bounce
// removed the spheres scene's fireflies), and at or above which a surface without a glass
// lobe or a smooth coat receives the light tracer's paths (alpha 0.04: its lobe's peak,
// 199, bounds what one connection to the eye weighs).
inline constexpr float kCausticCasterRoughness = 0.3f;
inline constexpr float kCausticReceiverRoughness = 0.2f;

// The most receivers a light path meets one after another beyond the caster, each seen by
// the eye: x1, then what x1 scatters the light onto (the sun's caustic on the floor lighting
// a sphere's underside), and so on. Next-event estimation leaves a caster's lobe out where the
// path's vertices before it are that many receivers or fewer.
inline constexpr int kCausticReceivers = 2;

// x2 of a light-traced path: the plain metallic-roughness BRDF (no glass, coat or sheen)
// with a smooth specular lobe.
bool causticCaster(const BsdfParams& b);
// x1 of a light-traced path: no smooth lobe of any kind.
bool causticReceiver(const BsdfParams& b);

// Whether 'scene' has caustics for the light tracer: a directional light and a material that
// can cast one (what CausticSources would find).
bool hasLightTracedCaustics(const Scene& scene);

// Light paths per eye and frame: one per kCausticSamplesPerPath camera samples (pixels x
// samples per pixel), so that the light tracer's share of the error falls with --spp as the
// path tracer's does (a reference at 4 spp a frame gets 4 times the paths a frame).
inline constexpr int kCausticSamplesPerPath = 8;
uint32_t causticPathCount(int width, int height, int samplesPerPixel = 1);

// What one light path adds to one pixel, before the division by the path count.
struct CausticSplat {
  uint32_t pixel = ~0u;  // ~0u: the path added nothing
  glm::vec3 diffuse{0.0f}, specular{0.0f};
};

// The directional lights and the casters' bounding spheres of 'scene' as it is posed now,
// from which light paths start: empty() when the scene has no caustics for light tracing
// (no directional light, or no material that can cast one).
class CausticSources {
 public:
  // 'world': bounds of everything a ray can meet (EmbreeScene::bounds), beyond which the
  // light paths start.
  CausticSources(const Scene& scene, const Bounds& world);
  bool empty() const { return suns_.empty() || casters_.empty(); }

  struct Start {
    glm::vec3 origin{0.0f}, toSun{0.0f};
    glm::vec3 irradiance{0.0f};  // the sun's, normal to it
    float pdf = 0.0f;            // of the start's point, per area of the plane normal to toSun
  };
  // A start for numbers uSun, uCaster in [0, 1) and uDisk in [0, 1)^2.
  Start sample(float uSun, float uCaster, glm::vec2 uDisk) const;

 private:
  struct Sun {
    glm::vec3 toSun, irradiance;
    float probability;
  };
  struct Caster {
    glm::vec3 centre;
    float radius;
  };
  std::vector<Sun> suns_;
  std::vector<Caster> casters_;
  std::vector<float> casterCdf_;  // by r^2, the disks' areas
  float diskArea_ = 0.0f;         // pi sum r^2
  Bounds world_;                  // what a ray can meet (the constructor's 'world')
  float worldMargin_ = 0.0f;      // how far beyond it a start begins
};

// A receiver a light path reached, what the eyes connect to: x1 (or a later receiver) as a
// hit record, the direction it arrived along and the light's throughput there, per its area.
struct CausticLight {
  HitRef x1;
  glm::vec3 w{0.0f};
  glm::vec3 beta{0.0f};
};

// One frame's light paths, traced once for both eyes of a stereo frame (the eye traced
// second connects the first's paths to itself): path k's r-th receiver is in slot
// k x kCausticReceivers + r, where reached[slot].
struct CausticPaths {
  struct Key {
    const Scene* scene = nullptr;
    const void* embree = nullptr;
    uint32_t seed = 0, frame = ~0u, count = 0;
  } key;
  std::vector<CausticLight> lights;
  std::vector<uint8_t> reached;
  // Whether these are the paths of 'frame' (of 'count' paths) in this context.
  bool holds(const TraceContext& ctx, uint32_t frame, uint32_t count) const;
};

// This frame's light paths (numbers keyed by the seed and frame alone, so both eyes trace
// the same paths), each receiver connected to 'camera': a splat per slot (CausticPaths).
std::vector<CausticSplat> traceCaustics(const TraceContext& ctx, const CausticSources& sources,
                                        const EyeCamera& camera, uint32_t frame, uint32_t pathCount,
                                        uint64_t* rays = nullptr);

// Adds the splats of 'pathCount' light paths, each divided by that count, to the pixels they
// land on that took samples: colour, and the demodulated lobes where the image has them.
void addCaustics(EyeImage& image, std::span<const CausticSplat> splats, uint32_t pathCount);

// Both, where ctx.settings.caustics is on, maxBounces reaches a second vertex and the scene
// has caustics to trace. 'shared':
// the frame's light paths, traced here unless it holds them already (the other eye's), and
// kept there; null: traced for this eye alone.
void traceCausticsInto(const TraceContext& ctx, const EyeCamera& camera, uint32_t frame,
                       EyeImage& image, CausticPaths* shared = nullptr);

}  // namespace photovr
