// Primary hits rebuilt from the G-buffer's visibility record: the record names the instance
// and triangle; the pixel's own jittered ray is intersected with that one triangle from the
// scene's vertex data — the computation a ray tracer performs — so the hit is exact to float
// rounding and no precision is lost to depth-buffer reconstruction.
#pragma once

#include <cstdint>
#include <span>

#include "core/camera.h"
#include "core/scene.h"
#include "core/visibility.h"
#include "gl/gbuffer.h"
#include "trace/surface.h"

namespace photovr {

struct RebuiltHit {
  SurfaceHit surface;
  glm::vec3 direction{0.0f};  // the pixel's ray (rebuildPrimaryHits: every pixel's, hit or not)
  float t = 0.0f;             // ray distance to the hit
  bool outside = false;       // the ray missed the named triangle (shared-edge disagreement)
};

// 'record' must be valid for 'scene'. Barycentrics of a ray that misses the triangle by a
// rounding error (raster and ray casting disagree on a shared edge) are clamped into it and
// the hit is flagged 'outside', so the disagreement is counted, not hidden (namedHit).
RebuiltHit rebuildPrimaryHit(const Scene& scene, const VisibilityRecord& record,
                             const glm::vec3& origin, const glm::vec3& direction);

// rebuildPrimaryHit for pixels [begin, end) of 'g', each along rays.pixelRay from 'origin',
// bit for bit: hits[i - begin] for pixel i (hits.size() >= end - begin); where the record
// names nothing in 'scene', RebuiltHit{} with the pixel's ray direction; where it saw nothing
// (the background), the direction alone, the rest left as it was. The tracer's loop reads the
// direction of every pixel (the background's environment) instead of computing it again.
// The rays' intersections and geometry run eight at a time in SIMD lanes (namedHits). Returns how
// many hits were flagged outside. 'materials': the scene's (MaterialTable(scene), or the
// tracer's EmbreeScene::materials()).
uint64_t rebuildPrimaryHits(const Scene& scene, const MaterialTable& materials,
                            const gl::GBufferImage& g, const CameraRays& rays,
                            const glm::vec3& origin, size_t begin, size_t end,
                            std::span<RebuiltHit> hits);

}  // namespace photovr
