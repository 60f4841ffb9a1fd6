// A surface point the tracer shades: position, normals, material inputs at the hit. Built
// from (instance, triangle, barycentrics) — the same record the G-buffer stores — so the
// pure path tracer and the hybrid start from identical data.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "trace/bsdf.h"
#include "trace/hit_geometry.h"

namespace photovr {

struct SurfaceHit {
  glm::vec3 position{0.0f};         // world
  glm::vec3 geometricNormal{0.0f};  // world, unit, facing the side the ray came from
  glm::vec3 shadingNormal{0.0f};    // world, unit, normal-mapped, same side as geometricNormal
  float positionError = 0.0f;       // bound on |position - exact|, for the ray offset
  BsdfParams bsdf;
  glm::vec3 emission{0.0f};  // emitted radiance towards the viewer (front faces only)
  uint32_t instance = 0, triangle = 0;
  bool frontFace = true;  // the ray hit the counter-clockwise side
};

// The BSDF inputs and emission of each material that reads no texture: constant over its
// surface, so the tracer computes them once per scene (EmbreeScene::materials) instead of at
// every hit: with materialAt's clamps, Material::iorF0's double division and textured()'s
// walk over 13 slots, surfaceAt was 8 % of the reusing eye's tracer samples on spheres, 4.5 %
// with the table (docs/MEASUREMENTS.md). The entries are what surfaceAt computes, to the bit.
struct ConstantMaterial {
  BsdfParams bsdf;  // as seen from the front (surfaceAt inverts eta on a volume's back)
  glm::vec3 emission[2]{glm::vec3(0.0f), glm::vec3(0.0f)};  // to a viewer on the back, front
};
class MaterialTable {
 public:
  MaterialTable() = default;
  explicit MaterialTable(const Scene& scene);
  // Null for a textured material (its inputs vary over its surface).
  const ConstantMaterial* constantOf(size_t material) const {
    return constant_[material] ? &constants_[material] : nullptr;
  }

 private:
  std::vector<ConstantMaterial> constants_;
  std::vector<uint8_t> constant_;
};

// 'incoming' is the direction the ray travelled (towards the surface).
SurfaceHit surfaceAt(const Scene& scene, uint32_t instance, uint32_t triangle, float b1, float b2,
                     const glm::vec3& incoming);

// surfaceAt(...) without the shading inputs: position, its error bound, geometric normal,
// side and emission are surfaceAt's to the bit; shadingNormal and bsdf stay default. What
// the last hit of a path needs (its emission, MIS-weighted): 14 % of the bounce rays' hits
// end their path in atrium, 17 % in cornell, and need no normals or textures.
SurfaceHit surfaceEmissionAt(const Scene& scene, uint32_t instance, uint32_t triangle, float b1,
                             float b2, const glm::vec3& incoming);

// The same from a hit whose geometry is known (hitGeometry, or a batch's hitGeometries).
SurfaceHit surfaceAt(const Scene& scene, const HitRef& hit, const HitGeometry& geometry,
                     const glm::vec3& incoming);
// The same, taking an untextured material's inputs from 'materials' (built from 'scene').
SurfaceHit surfaceAt(const Scene& scene, const MaterialTable& materials, const HitRef& hit,
                     const HitGeometry& geometry, const glm::vec3& incoming);
SurfaceHit surfaceEmissionAt(const Scene& scene, const HitRef& hit, const HitGeometry& geometry,
                             const glm::vec3& incoming);

// Unit normal of the triangle with edges e1 = p1 - p0, e2 = p2 - p0 (counter-clockwise
// side), +Y for a degenerate one: the geometric normal surfaceAt() starts from.
glm::vec3 unitGeometricNormal(const glm::vec3& e1, const glm::vec3& e2);

// surfaceAt(...).emission without the rest of the surface (light sampling needs only this):
// 'geometricNormal' is unitGeometricNormal() of the triangle's world edges.
glm::vec3 emissionAt(const Scene& scene, uint32_t instance, uint32_t triangle, float b1, float b2,
                     const glm::vec3& geometricNormal, const glm::vec3& incoming);

// glTF alpha at a point of a triangle of 'mesh' (material's base colour factor x texture
// alpha): what the any-hit filter tests against MASK's cutoff and BLEND's coin.
float surfaceAlpha(const Scene& scene, const Mesh& mesh, const Material& material,
                   uint32_t triangle, float b1, float b2);

// The probability that a ray meets the surface at this point instead of passing through it,
// as the any-hit filter decides: MASK 0 in its holes and 1 elsewhere, BLEND its alpha,
// opaque 1. Light sampling scales an emitter's radiance by it, so that NEE sees on average
// what BSDF rays see (an emitter's hole or a half-transparent emitter is not counted whole).
float coverageAt(const Scene& scene, uint32_t instance, uint32_t triangle, float b1, float b2);

// Origin for a ray leaving 'hit' along 'dir': the hit moved off the surface along the
// geometric normal by its error bound (Wachter & Binder, "A Fast and Robust Method for
// Avoiding Self-Intersection", Ray Tracing Gems ch. 6, 2019: integer-ulp offset far from
// the origin, a fixed float offset near it).
glm::vec3 offsetRayOrigin(const SurfaceHit& hit, const glm::vec3& dir);

// Emitted radiance of a material at a hit seen from 'toViewer' (glTF emission is one-sided
// for single-sided materials, two-sided for double-sided ones).
glm::vec3 emittedRadiance(const Scene& scene, const SurfaceHit& hit);

}  // namespace photovr
