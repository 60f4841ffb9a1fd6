// The environment-lit glTF scenes of bench_sampler (issue 18): built in code, written as
// .glb and an .hdr panorama, and read back through photovr's own loaders, so that the
// bench measures what a user's `--scene model.glb --env panorama.hdr` renders.
//   metal-gltf     five metallic spheres (roughness 0.05 .. 0.8) and a brushed arch on a
//                  rough floor, under an outdoor panorama (gradient sky and a small sun);
//   textured-gltf  textured boxes, a cylinder and a glossy sphere on a checker floor, under
//                  a studio panorama (dark surround, two soft boxes and a strip light).
#pragma once

#include <string>
#include <vector>

#include "core/scene.h"

namespace photovr::bench {

std::vector<std::string> gltfSceneNames();  // {"metal-gltf", "textured-gltf"}
bool isGltfScene(const std::string& name);

// Writes <dir>/<name>.glb and <dir>/<name>.hdr (replacing older ones) and loads them back
// with loadGltf and loadEnvironment. Throws InputError for a file it cannot write or read.
Scene makeGltfScene(const std::string& name, const std::string& dir);

}  // namespace photovr::bench
