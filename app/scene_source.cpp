#include <filesystem>
#include <iostream>

#include "app/commands.h"
#include "core/builtin_scenes.h"
#include "core/environment_io.h"
#include "core/error.h"
#include "core/gltf_loader.h"
#include "core/scene_info.h"

namespace photovr::app {

static std::string builtinList() {
  std::string list;
  for (const std::string& n : builtinSceneNames()) list += (list.empty() ? "" : ", ") + n;
  return list;
}

Scene loadSceneSpec(const std::string& spec) {
  if (isBuiltinScene(spec)) return makeBuiltinScene(spec);
  const std::string ext = std::filesystem::path(spec).extension().string();
  if (ext != ".gltf" && ext != ".glb") {
    if (!std::filesystem::exists(spec))
      throw UsageError("--scene: '" + spec + "' is neither a built-in scene (" + builtinList() +
                       ") nor an existing .gltf/.glb file");
    throw InputError(spec, "not a glTF file (expected .gltf or .glb)");
  }
  Scene scene = loadGltf(spec);
  for (const std::string& w : scene.warnings) std::cerr << "photovr: warning: " << w << "\n";
  return scene;
}

void warnAboutScene(const Scene& scene) {
  for (const std::string& w : analyzeScene(scene).warnings)
    std::cerr << "photovr: warning: " << w << "\n";
}

void applyEnvironmentOption(Scene& scene, const std::string& envPath) {
  if (envPath.empty()) return;
  std::string warning;
  scene.environment = loadEnvironment(envPath, &warning);
  if (!warning.empty()) std::cerr << "photovr: warning: " << warning << "\n";
}

double applyTimeOption(Scene& scene, const Options& options) {
  const double t = options.number("--time", 0.0f, 0.0f, 1e6f);
  if (!isAnimated(scene)) {
    if (options.has("--time"))
      std::cerr << "photovr: warning: --time: the scene has no animation; it is rendered as is\n";
    return t;
  }
  poseScene(scene, t, t - kAnimationFrameSeconds);
  return t;
}

bool wantsHelp(const Args& args) {
  for (const std::string& a : args)
    if (a == "--help" || a == "-h") return true;
  return false;
}

}  // namespace photovr::app
