#include "trace/environment_sampling.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace photovr {
namespace {

// The map pixel containing (u, v); u wraps around, v clamps at the poles.
// Must pick the same cell as Distribution2D::pdf() does for (u - floor(u), 1 - v).
glm::ivec2 pixelOf(glm::vec2 uv, int width, int height) {
  return {cellIndex(uv.x - std::floor(uv.x), width), cellIndex(1.0f - uv.y, height)};
}

// An environment that depends on the elevation alone (Sky, Constant): the luminance at the
// centre of each of n equal bands of y = d.y, band k being y in [-1 + 2k/n, -1 + 2(k+1)/n).
// n is even, so the horizon y = 0 is a band edge; the sky's blend is linear in y above it,
// so a band's centre holds its mean.
std::vector<float> zoneWeights(const Environment& env, int n) {
  std::vector<float> f(size_t(n), 0.0f);
  for (int k = 0; k < n; ++k) {
    const float y = -1.0f + 2.0f * (float(k) + 0.5f) / float(n);
    const float l = luminance(lookupEnvironment(env, {std::sqrt(1.0f - y * y), y, 0.0f}));
    if (isFinite(l) && l > 0.0f) f[size_t(k)] = l;
  }
  return f;
}

// Luminance * sin(theta at the row centre) per pixel, row 0 at the top (theta = 0).
std::vector<float> samplingWeights(const std::vector<glm::vec3>& pixels, int w, int h) {
  std::vector<float> f(size_t(w) * h);
  for (int j = 0; j < h; ++j) {
    const float sinTheta = std::sin(kPi * (float(j) + 0.5f) / float(h));
    for (int i = 0; i < w; ++i) {
      const float l = luminance(pixels[size_t(j) * w + i]);
      f[size_t(j) * w + i] = isFinite(l) && l > 0.0f ? l * sinTheta : 0.0f;
    }
  }
  return f;
}

}  // namespace

glm::vec2 directionToEquirect(const glm::vec3& d) {
  const float len = glm::length(d);
  const float y = len > 0.0f ? std::clamp(d.y / len, -1.0f, 1.0f) : 0.0f;
  return {0.5f + std::atan2(d.z, d.x) * kInv2Pi, 0.5f + std::asin(y) * kInvPi};
}

glm::vec3 equirectToDirection(glm::vec2 uv) {
  const float phi = 2.0f * kPi * (uv.x - 0.5f);  // azimuth from +X towards +Z
  const float elevation = kPi * (uv.y - 0.5f);   // from the horizon towards +Y
  const float c = std::cos(elevation);
  return {c * std::cos(phi), std::sin(elevation), c * std::sin(phi)};
}

glm::vec3 skyRadiance(const Environment& env, const glm::vec3& d) {
  const float len = glm::length(d);
  const float y = len > 0.0f ? d.y / len : 0.0f;
  if (!(y >= 0.0f)) return env.groundColor;  // also for a NaN direction
  return glm::mix(env.horizonColor, env.zenithColor, std::min(y, 1.0f));
}

glm::vec3 lookupEnvironment(const Environment& env, const glm::vec3& d) {
  switch (env.type) {
    case Environment::Type::None:
      return glm::vec3(0.0f);
    case Environment::Type::Constant:
      return env.constant * env.intensity;
    case Environment::Type::Sky:
      return skyRadiance(env, d) * env.intensity;
    case Environment::Type::Map: {
      if (env.width <= 0 || env.height <= 0 || env.pixels.empty()) return glm::vec3(0.0f);
      const glm::ivec2 p = pixelOf(directionToEquirect(d), env.width, env.height);
      return env.pixels[size_t(p.y) * env.width + p.x] * env.intensity;
    }
  }
  return glm::vec3(0.0f);
}

EnvironmentSampler::EnvironmentSampler(const Environment& env) : env_(&env) {
  if (env.type == Environment::Type::None) return;
  if (env.type == Environment::Type::Map) {
    if (env.width <= 0 || env.height <= 0 ||
        env.pixels.size() != size_t(env.width) * size_t(env.height))
      return;
    distribution_ =
        Distribution2D(samplingWeights(env.pixels, env.width, env.height), env.width, env.height);
    return;
  }
  zones_ = Distribution1D(zoneWeights(env, kZones));
}

EnvironmentSample EnvironmentSampler::sample(glm::vec2 u) const {
  EnvironmentSample s;
  if (empty()) return s;
  if (zones_.size() > 0) {
    // A band by the 1D density, y uniform within it, the azimuth uniform: dw = dy dphi.
    const float y = std::clamp(2.0f * zones_.sampleContinuous(u.y).x - 1.0f, -1.0f, 1.0f);
    const float r = std::sqrt((1.0f - y) * (1.0f + y));
    const float phi = 2.0f * kPi * u.x;
    s.direction = {r * std::cos(phi), y, r * std::sin(phi)};
  } else {
    const Distribution2D::Sample d = distribution_.sample(u);
    // Distribution coordinates are (u, 1 - v): row 0 of the table is the top (v = 1).
    s.direction = equirectToDirection({d.p.x, 1.0f - d.p.y});
  }
  // pdf() and lookup from the direction, not from the cell drawn, so that a direction
  // sampled here and the same direction found by a BSDF ray get the same pdf and radiance
  // (MIS needs the two to agree), even where rounding moves it across a pixel edge.
  s.pdf = pdf(s.direction);
  if (s.pdf > 0.0f) s.radiance = lookupEnvironment(*env_, s.direction);
  return s;
}

float EnvironmentSampler::pdf(const glm::vec3& direction) const {
  if (empty()) return 0.0f;
  if (zones_.size() > 0) {
    // Density p(x) over x = (1 + y) / 2 in [0, 1]: dw = dy dphi = 2 dx dphi, so the solid
    // angle density is p(x) / (4 pi).
    const float len = glm::length(direction);
    const float y = len > 0.0f ? std::clamp(direction.y / len, -1.0f, 1.0f) : 0.0f;
    return zones_.pdf(0.5f * (1.0f + y)) * (0.25f * kInvPi);
  }
  const glm::vec2 uv = directionToEquirect(direction);
  // dw = sin(theta) dtheta dphi = 2 pi^2 sin(theta) du dv (pbrt sec. 12.5.3, eq. 12.12).
  const float theta = kPi * (1.0f - uv.y);
  const float sinTheta = std::sin(theta);
  if (!(sinTheta > 0.0f)) return 0.0f;
  const float p = distribution_.pdf({uv.x - std::floor(uv.x), 1.0f - uv.y});
  return p / (2.0f * kPi * kPi * sinTheta);
}

}  // namespace photovr
