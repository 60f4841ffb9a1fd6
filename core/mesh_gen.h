// Mesh generators for the built-in scenes and for tests.
//
// Every generator returns a closed or open triangle list with counter-clockwise winding seen
// from the front (outside), unit per-vertex normals that agree with that winding, and uv0.
// Material index is 0; callers set it. Units are metres, +Y up.
#pragma once

#include <string>

#include "core/scene.h"

namespace photovr {

// A parallelogram origin, origin + edgeU, origin + edgeU + edgeV, origin + edgeV. Its front
// faces along cross(edgeU, edgeV). uv (0,1) at origin, u along edgeU, v decreasing along edgeV
// (glTF's uv origin is the image's top-left), so an image appears upright when edgeV points up.
Mesh makeQuad(const glm::vec3& origin, const glm::vec3& edgeU, const glm::vec3& edgeV);

// Axis-aligned box with flat faces, outward normals and a full [0,1] uv square per face.
Mesh makeBox(const glm::vec3& min, const glm::vec3& max);

// Sphere centred at the origin. segments around +Y (>= 3), rings from pole to pole (>= 2).
// Smooth normals; u = longitude / 2pi, v = 0 at the north (+Y) pole.
Mesh makeUvSphere(float radius, int segments, int rings);

// Cylinder around +Y from y = 0 to y = height. rings = rows of quads along the side (>= 1).
// Smooth side normals; flat caps with their own vertices when capped.
Mesh makeCylinder(float radius, float height, int segments, int rings, bool capped);

// Semicircular arch: the half-annulus innerRadius <= r <= innerRadius + thickness, y >= 0, in
// the XY plane centred at the origin, extruded along Z over [-depth/2, depth/2]. A closed
// solid: extrados, intrados (smooth), front, back and the two feet at y = 0 (flat).
Mesh makeArch(float innerRadius, float thickness, float depth, int segments);

// Applies a model matrix to positions and its inverse transpose to normals (and tangents'
// xyz), renormalising; a mirroring matrix also reverses the winding to keep front faces.
void transformMesh(Mesh& mesh, const glm::mat4& transform);

// Appends src's triangles to dst. Attributes present in only one of them are dropped.
void appendMesh(Mesh& dst, const Mesh& src);

// Reverses the winding and negates normals: turns an outward box into a room.
void flipMesh(Mesh& mesh);

// Sum of triangle areas, in double for test accuracy.
double meshSurfaceArea(const Mesh& mesh);

// Signed enclosed volume (divergence theorem); positive for a closed, outward-wound mesh.
double meshSignedVolume(const Mesh& mesh);

}  // namespace photovr
