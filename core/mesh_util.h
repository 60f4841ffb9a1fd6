// Mesh preparation shared by the glTF loader and the built-in scenes.
#pragma once

#include <string>

#include "core/scene.h"

namespace photovr {

// Checks what the renderer relies on and throws InputError(file, "mesh 'name': ...") on the
// first violation: positions/normals/uvs finite, attribute arrays the same length, index
// count a multiple of 3, every index in range, and at least one triangle of non-zero area.
void validateMesh(const Mesh& mesh, const std::string& file);

// Area-weighted vertex normals for meshes that have none (glTF §3.7.2.1: flat normals are
// the spec's default; smooth-by-area is used only for meshes generated in code).
void computeVertexNormals(Mesh& mesh);

// Flat normals: un-shares vertices so every triangle gets its face normal, as glTF requires
// when NORMAL is absent.
void makeFlatShaded(Mesh& mesh);

// Per-vertex tangents from uv0 (Lengyel's method, "Mathematics for 3D Game Programming",
// §7.8), Gram-Schmidt orthogonalised against the normal, w = handedness. glTF asks for
// MikkTSpace; Debian ships no MikkTSpace package and for smooth, well-parametrised meshes
// the two agree closely, so this is documented as an approximation.
void computeTangents(Mesh& mesh);

// Count of triangles whose area is zero (or not finite) in object space.
size_t degenerateTriangleCount(const Mesh& mesh);

}  // namespace photovr
