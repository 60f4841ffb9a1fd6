// Scenes generated in code, so that every renderer feature can be run and tested without
// asset files:
//   cornell  closed 2 m box, one area light (emissive quad), metal and rough boxes;
//   spheres  5 x 5 roughness x metallic sweep under a sky and a sun (directional light);
//   atrium   two-storey instanced colonnade (the Sponza stand-in, > 200k triangles) with a
//            textured floor, an alpha-masked double-sided lattice, point lights, open roof.
// Each scene carries exactly one camera, "<name>-view": the built-in scene's own view.
#pragma once

#include <string>
#include <vector>

#include "core/scene.h"

namespace photovr {

// {"atrium", "cornell", "spheres"}, sorted.
std::vector<std::string> builtinSceneNames();

bool isBuiltinScene(const std::string& name);

// Builds the named scene; deterministic (two calls give identical data). Throws UsageError
// naming the valid scenes for an unknown name.
Scene makeBuiltinScene(const std::string& name);

}  // namespace photovr
