// The environment seen by rays that leave the scene: lookup by direction and importance
// sampling in proportion to its radiance (pbrt 4th ed., sec. 12.5.3, ImageInfiniteLight).
//
// Mapping: the latitude-linear equirectangular projection of downloadable panoramas,
// oriented as Blender and three.js (issue 3): for a direction d in glTF axes (+Y up),
//   u = 0.5 + atan2(d.z, d.x) / (2 pi),   v = 0.5 + asin(d.y) / pi,
// v = 1 at the top row, so a pixel (column i, row j) of a W x H map covers
// u in [i/W, (i+1)/W) and v in (1 - (j+1)/H, 1 - j/H]. (Not the thesis's equal-area
// v = (1 + sin phi) / 2.) theta below is the polar angle from +Y: theta = pi (1 - v).
#pragma once

#include <glm/glm.hpp>

#include "core/scene.h"
#include "trace/sampling.h"

namespace photovr {

// d need not be unit length (it is normalised); u in [0,1], v in [0,1].
glm::vec2 directionToEquirect(const glm::vec3& d);
glm::vec3 equirectToDirection(glm::vec2 uv);  // unit length

// Radiance arriving from direction d (pointing away from the scene, towards the sky):
//   None: 0.  Constant: constant * intensity.
//   Map: the pixel containing d (nearest, no filtering) * intensity. Nearest because the
//     sampling density below is constant over each pixel: L / pdf is then constant over
//     a pixel's rows of equal sin(theta), so the map adds no variance of its own, and
//     sample() returns exactly the radiance a BSDF ray in the same direction sees.
//   Sky: skyRadiance(env, d) * intensity.
glm::vec3 lookupEnvironment(const Environment& env, const glm::vec3& d);

// The analytic gradient sky of the built-in scenes, before intensity. Above the horizon
// horizonColor blends linearly in d.y = sin(elevation) to zenithColor at the top; below it
// is groundColor (a sharp horizon, as a ground plane seen from above it). With the
// built-in clear sky this puts ~0.29 pi of luminance irradiance on the ground, the figure
// core/builtin_scenes.cpp designs it for. No sun disc: the sun is a directional light.
glm::vec3 skyRadiance(const Environment& env, const glm::vec3& d);

struct EnvironmentSample {
  glm::vec3 direction{0.0f};  // unit, towards the environment
  glm::vec3 radiance{0.0f};   // lookupEnvironment(direction)
  float pdf = 0.0f;           // solid angle; pdf(direction); 0 = no sample
  bool valid() const { return pdf > 0.0f; }
};

// Importance sampling in proportion to the radiance per solid angle, by one of two
// piecewise-constant densities:
//  - Map: a 2D density over the equirect (u, 1 - v) square in proportion to pixel
//    luminance * sin(theta at the row centre), the Jacobian of the mapping (pbrt sec.
//    12.5.3), so that L / pdf is constant over each pixel's rows of equal sin(theta).
//  - Sky and Constant, which depend on the elevation alone: a 1D density over y = d.y in
//    kZones bands of equal solid angle (Archimedes: dw = dy dphi), the azimuth uniform.
//    pdf() is a band lookup with no trigonometry and sample() takes one sincos; the 2D
//    table they were tabulated on before spent an atan2, an asin and a sin in every pdf()
//    and two table searches per sample, ~14 % of atrium's tracer (docs/MEASUREMENTS.md).
class EnvironmentSampler {
 public:
  // 64 bands, 32 above the horizon (the band edge y = 0), of 1/32 in sin(elevation): the
  // gradient sky's only feature is its horizon, which is an edge; it has no sun disc.
  static constexpr int kZones = 64;

  EnvironmentSampler() = default;
  explicit EnvironmentSampler(const Environment& env);  // keeps a pointer to env

  bool empty() const { return env_ == nullptr || (distribution_.empty() && zones_.size() == 0); }
  EnvironmentSample sample(glm::vec2 u) const;
  float pdf(const glm::vec3& direction) const;  // solid angle density of sample()

 private:
  const Environment* env_ = nullptr;
  Distribution2D distribution_;  // Map
  Distribution1D zones_;         // Sky, Constant: over x = (1 + y) / 2
};

}  // namespace photovr
