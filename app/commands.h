// The photovr subcommands. Each takes the arguments after its name and returns the exit
// status; errors are thrown (UsageError, InputError, gl::ContextError) and reported by main.
#pragma once

#include <string>
#include <vector>

#include "core/options.h"
#include "core/scene.h"

namespace photovr::app {

using Args = std::vector<std::string>;

int runRender(const Args& args);
int runInfo(const Args& args);
int runExportScene(const Args& args);
int runAb(const Args& args);
int runReference(const Args& args);
int runStress(const Args& args);
int runBench(const Args& args);
int runView(const Args& args);

// A built-in scene name or a .gltf/.glb path; --env FILE replaces the environment.
Scene loadSceneSpec(const std::string& spec);
void applyEnvironmentOption(Scene& scene, const std::string& envPath);
// --time T: an animated scene posed at T seconds (core/animation.h), its instances' previous
// transforms one headset frame (kAnimationFrameSeconds) before, for the G-buffer's motion
// vectors. Returns T, where the scene clock of a sequence starts.
double applyTimeOption(Scene& scene, const Options& options);
// The scene's own warnings (core/scene_info.h: no light, meshes not drawn, ...) on stderr,
// for the commands that render it, once the environment option is applied.
void warnAboutScene(const Scene& scene);

bool wantsHelp(const Args& args);

}  // namespace photovr::app
