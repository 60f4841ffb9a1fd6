// Camera-relative coordinates: float positions 1e5 m from the origin are 8 mm apart, so a
// renderer that keeps world coordinates cannot draw a small room there. Moving the whole
// scene so the viewer sits at the origin (offsets applied in double) keeps full precision
// where the image is made — the "floating origin" of large-world engines.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/scene.h"

namespace photovr {

// Moves every instance, light and camera by 'offset' (computed in double per component);
// the scene's origin moves the other way, so it still names the same place of the file.
void translateScene(Scene& scene, const glm::dvec3& offset);

// Where a loader placed the scene's parts, composed in double: one transform per instance,
// one position per light and per camera, in the scene's order.
struct DoublePlacement {
  std::vector<glm::dmat4> instances;
  std::vector<glm::dvec3> lights, cameras;
};

// Whether float coordinates of a scene reaching 'reach' from its zero, 'extent' across,
// are coarser than 'fraction' of the extent (the spacing of floats at 'reach' above it).
bool floatsTooCoarse(double reach, double extent, double fraction);

// Stores 'placed' in the scene's float transforms and positions. When floats at the
// content's distance from the file's zero are coarser than 2^-16 of its extent, the scene
// is first re-based at the centre of its bounds (computed in double; scene.origin set to
// it), so a file 1e7 m out keeps the precision it has at the origin. Returns false when
// the geometry reaches beyond float range even so.
bool storePlacement(Scene& scene, const DoublePlacement& placed);

// Translates the scene so that 'view' is at the origin; returns the view there.
Pose recenterOnView(Scene& scene, const Pose& view);

}  // namespace photovr
