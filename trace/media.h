// The media a path travels through (KHR_materials_volume): the volumes it has entered and
// not yet left, innermost last, after Schmidt & Budge, "Simple Nested Dielectrics in Ray
// Traced Images", JGT 7(2), 2002, without their priorities (a volume inside another is
// entered after it). It decides the relative index of refraction at each interface and the
// absorption along each segment, so that glass in water, or ice in a glass of water, bends
// and absorbs light as the nesting says.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace photovr {

struct MediumStack {
  // Deeper nesting than this is not tracked: a fifth volume entered is treated as its
  // container's medium (rare in real scenes; documented in docs/ARCHITECTURE.md).
  static constexpr int kDepth = 4;
  uint32_t instance[kDepth] = {};
  uint8_t size = 0;

  // The medium a path leaving 'instance's volume enters: the innermost other volume it is
  // in, or air (kNone).
  static constexpr uint32_t kNone = ~0u;
  uint32_t outsideOf(uint32_t volume) const;
  uint32_t current() const { return size ? instance[size - 1] : kNone; }
  void enter(uint32_t volume);
  void leave(uint32_t volume);
};

// A volume's material, or null where 'instance' is no volume (or kNone: air).
const Material* volumeMaterial(const Scene& scene, uint32_t instance);
// Index of refraction and absorption coefficient of a medium (kNone: air, 1 and 0).
float mediumIor(const Scene& scene, uint32_t instance);
glm::vec3 mediumAbsorption(const Scene& scene, uint32_t instance);

// The glass lobe's relative index at a hit on volume 'instance' for a path in 'media':
// entering (front face) ior / ior(current medium), leaving (back face) ior(outside) / ior.
float relativeEta(const Scene& scene, const MediumStack& media, uint32_t instance, bool frontFace);

}  // namespace photovr
