// Rebuilding surface hits from a visibility record (instance, triangle, barycentrics).
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace photovr {

// The instance a pixel that saw no surface records (shaders/gbuffer.frag clears to it).
constexpr uint32_t kNoHitInstance = 0xFFFFFFFFu;

struct VisibilityRecord {
  uint32_t instance = kNoHitInstance;  // index into Scene::instances
  uint32_t triangle = 0;
  float b1 = 0.0f, b2 = 0.0f;  // barycentrics of vertices 1 and 2
  bool hit() const { return instance != kNoHitInstance; }
};

// World-space triangle of an instance.
struct WorldTriangle {
  glm::vec3 p0, p1, p2;
};
WorldTriangle worldTriangle(const Scene& scene, uint32_t instance, uint32_t triangle);

// p0 + b1 (p1 - p0) + b2 (p2 - p0) in world space; the record must be in range.
glm::vec3 rebuildHitPoint(const Scene& scene, const VisibilityRecord& record);

// True when the record names an existing instance and triangle.
bool isValidRecord(const Scene& scene, const VisibilityRecord& record);

}  // namespace photovr
