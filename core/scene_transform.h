// Camera-relative coordinates: float positions 1e5 m from the origin are 8 mm apart, so a
// renderer that keeps world coordinates cannot draw a small room there. Moving the whole
// scene so the viewer sits at the origin (offsets applied in double) keeps full precision
// where the image is made — the "floating origin" of large-world engines.
#pragma once

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/scene.h"

namespace photovr {

// Moves every instance, light and camera by 'offset' (computed in double per component).
void translateScene(Scene& scene, const glm::dvec3& offset);

// Translates the scene so that 'view' is at the origin; returns the view there.
Pose recenterOnView(Scene& scene, const Pose& view);

}  // namespace photovr
