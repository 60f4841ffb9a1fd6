// What a scene contains and which renderer features it needs: the summary `photovr info`
// prints, and the flags later stages read to skip work (no shadow rays without punctual
// lights, no light sampling of triangles without emitters, no any-hit filter without MASK).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/scene.h"

namespace photovr {

struct SceneFeatures {
  bool punctualLights = false;  // any KHR punctual light: shadow rays towards them
  bool areaLights = false;      // any instanced triangle with an emissive material
  bool environment = false;     // misses return sky/map/constant radiance (else black)
  bool unlitSurfaces = false;   // an instanced KHR_materials_unlit surface shows its colour
  bool alphaMask = false;       // a MASK material is instanced: any-hit alpha test
  bool alphaBlend = false;      // a BLEND material is instanced
  bool doubleSided = false;     // a double-sided material is instanced
  bool singleSided = false;     // ... a single-sided one: camera rays cull its back faces
  size_t pointLights = 0, spotLights = 0, directionalLights = 0;
  size_t emissiveTriangles = 0;       // instanced (world) triangles with emission: area lights
  size_t filteredMeshes = 0;          // meshes that need the any-hit filter (MASK, BLEND)
  std::vector<std::string> warnings;  // problems a person should hear about before rendering
};

SceneFeatures analyzeScene(const Scene& scene);

// Multi-line human summary (counts, materials by kind, textures, lights, cameras,
// environment, bounds) ending with a "renderer will use:" section built from analyzeScene.
std::string describeScene(const Scene& scene);

}  // namespace photovr
