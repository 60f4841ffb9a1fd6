// Which camera a rendering command uses: a scene camera (--camera), overridden by
// --look-from/--look-at/--fovy, placed as a stereo pair (--eyes stereo) or rendered with
// its own symmetric frustum (--eyes mono).
#pragma once

#include <array>
#include <string>

#include "core/options.h"
#include "core/camera.h"
#include "core/scene.h"

namespace photovr {

struct View {
  Pose head;
  float yfov = 1.0f;  // radians; mono only
  bool stereo = true;
  std::string description;  // for the log: which camera and how it was placed
};

// Throws UsageError for a camera index/name the scene lacks.
View resolveView(const Scene& scene, const Options& options);

// The two eye cameras of frame 'frame' (Halton jitter). Mono gives the same camera twice.
std::array<EyeCamera, 2> eyeCameras(const View& view, int width, int height, uint32_t frame,
                                    SamplerKind sampler);

// The options every rendering command accepts for the camera, with their help text: the
// head's placement (all commands) and the eyes (not `view`, whose eyes are the headset's).
extern const char* const kHeadHelp;
extern const char* const kEyesHelp;
extern const std::set<std::string> kViewOptions;

}  // namespace photovr
