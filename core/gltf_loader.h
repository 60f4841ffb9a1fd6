// glTF 2.0 import (.gltf with external or embedded buffers, and .glb) through tinygltf.
#pragma once

#include <string>

#include "core/scene.h"

namespace photovr {

// Loads the default scene (or scene 0) of a glTF 2.0 file, flattened to world-space
// instances: each primitive becomes one Mesh, stored once however many nodes use it.
// Supports PBR metallic-roughness materials with textures, KHR_texture_transform,
// KHR_materials_emissive_strength, _ior, _specular, _transmission, _unlit and _volume,
// KHR_lights_punctual and perspective cameras.
// Malformed files throw InputError("<path>: <problem>"); recoverable problems (a missing
// texture, an unsupported optional extension, points or lines) go to Scene::warnings.
Scene loadGltf(const std::string& path);

}  // namespace photovr
