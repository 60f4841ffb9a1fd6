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

// Not a listed built-in: cornell lit instead by a ceiling panel of 2048 emissive triangles
// under an emissive texture that is black but for a square 1/256 of the panel (emitting the
// cornell light's power): the textured-emitter case of issue 23, for the light set's test
// and bench_skips ("dark-emitters").
Scene makeCornellTexturedLight();

}  // namespace photovr
