// The geometric part of a surface hit — world position, its float error bound, the
// triangle's unit normal — for one hit or a batch: the wavefront tracer rebuilds every
// bounce hit's geometry in one vectorised pass (issue 20) before the rest of each surface
// (normals, textures, material) is read hit by hit. The batch computes each hit with the
// scalar code's operations in the scalar code's order, and without FMA contraction (the
// AVX2 clone does not enable FMA), so both give the same bits: surfaceAt is the same
// whichever built it.
#pragma once

#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "core/visibility.h"

namespace photovr {

// A ray's hit as Embree reports it: instance, triangle, barycentrics of vertices 1 and 2.
struct HitRef {
  uint32_t instance = 0, triangle = 0;
  float b1 = 0.0f, b2 = 0.0f;
};

struct HitGeometry {
  glm::vec3 position{0.0f};    // world
  float positionError = 0.0f;  // bound on |position - exact|
  glm::vec3 ng{0.0f};  // unit normal of the counter-clockwise side; +Y for a degenerate triangle
  // The vertex normals interpolated and taken to world space, unit, before any normal map;
  // ng where the mesh has none or they cancel out. Either side of the surface (surfaceAt
  // turns it to the viewer's).
  glm::vec3 normal{0.0f};
};

HitGeometry hitGeometry(const Scene& scene, const HitRef& hit);
// The same from the hit triangle's world-space corners (worldTriangle transforms the
// corners as hitGeometry does, bit for bit), which have no vertex normals: 'normal' is ng.
HitGeometry hitGeometry(const WorldTriangle& triangle, float b1, float b2);

// hitGeometry for every hit: out[i] for hits[i]; out.size() == hits.size().
void hitGeometries(const Scene& scene, std::span<const HitRef> hits, std::span<HitGeometry> out);

// A ray and the triangle it is known to hit: the hybrid's primary hits, whose G-buffer
// visibility record names the triangle and the rasterizer's barycentrics.
struct NamedRay {
  HitRef hit;  // the triangle; its barycentrics are kept where the ray runs parallel to it
  glm::vec3 direction{0.0f};
};
struct NamedHit {
  HitRef hit;            // barycentrics of the ray's hit, clamped into the triangle
  HitGeometry geometry;  // hitGeometry(scene, hit), bit for bit
  float t = 0.0f;        // dot(geometry.position - origin, direction)
  bool outside = false;  // the ray missed the triangle or ran parallel to it: clamped
};

// The ray from 'origin' intersected with its named triangle (Moller-Trumbore, 1997, without
// culling, in world space and float: the G-buffer shader's arithmetic, shaders/gbuffer.frag),
// barycentrics outside it clamped into it and flagged, so that raster-vs-ray disagreement on
// a shared edge is counted, not hidden. The record's instance and triangle must exist.
NamedHit namedHit(const Scene& scene, const glm::vec3& origin, const NamedRay& ray);
// namedHit for every ray, in SIMD lanes, bit for bit: out[i] for rays[i].
void namedHits(const Scene& scene, const glm::vec3& origin, std::span<const NamedRay> rays,
               std::span<NamedHit> out);

}  // namespace photovr
