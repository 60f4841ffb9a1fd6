// Shared fixtures for GL tests: one OSMesa context per test program (contexts are costly
// to create under llvmpipe), and tiny hand-built scenes with known answers.
#pragma once

#include <memory>

#include "core/scene.h"
#include "gl/context.h"

namespace photovr::testing {

gl::Context& osmesaContext();

// A rectangle in the plane z = 0 spanning [-hx, hx] x [-hy, hy], facing +Z, uv over [0,1]^2.
Mesh rectangleMesh(float hx, float hy, int material);

// Material with a constant base colour and the given roughness/metallic.
Material plainMaterial(glm::vec3 baseColor, float metallic = 0.0f, float roughness = 1.0f);

}  // namespace photovr::testing
