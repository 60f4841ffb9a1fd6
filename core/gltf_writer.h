// glTF 2.0 export of a Scene, for sharing scenes built in code and for round-trip tests.
#pragma once

#include <string>
#include <vector>

#include "core/scene.h"

namespace photovr {

// Writes the scene as a .glb, or as a .gltf with the buffer embedded as a data URI (chosen by
// the extension). Meshes are written once and instances become nodes with matrices that
// share them; textures are embedded as PNG; lights use KHR_lights_punctual. The file is
// written under a temporary name and renamed, so a failure leaves nothing half-written.
// Throws InputError naming the path. Returns warnings about what glTF cannot hold (the
// environment); the caller decides whether to print them.
std::vector<std::string> writeGlb(const Scene& scene, const std::string& path);

}  // namespace photovr
