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
};

HitGeometry hitGeometry(const Scene& scene, const HitRef& hit);
// The same from the hit triangle's world-space corners, where the caller has them
// (worldTriangle transforms the corners as hitGeometry does, bit for bit): the hybrid's
// primary hits, whose triangle is intersected first.
HitGeometry hitGeometry(const WorldTriangle& triangle, float b1, float b2);

// hitGeometry for every hit: out[i] for hits[i]; out.size() == hits.size().
void hitGeometries(const Scene& scene, std::span<const HitRef> hits, std::span<HitGeometry> out);

}  // namespace photovr
