// photovr info / export-scene: what a scene contains, and built-in scenes as glTF.
#include <filesystem>
#include <iostream>

#include "app/commands.h"
#include "core/options.h"
#include "core/builtin_scenes.h"
#include "core/error.h"
#include "core/gltf_writer.h"
#include "core/scene_info.h"

namespace photovr::app {

int runInfo(const Args& args) {
  if (wantsHelp(args)) {
    std::cout << "usage: photovr info SCENE [--env FILE]\n"
                 "Prints what a scene contains (meshes, instances, triangles, materials,\n"
                 "textures, lights, cameras, bounds) and what the renderer will use.\n"
                 "SCENE is a built-in name (atrium, cornell, spheres) or a .gltf/.glb file.\n";
    return 0;
  }
  const Options o(args, {"--env"}, {});
  if (o.positional().size() != 1) throw UsageError("info: expected exactly one SCENE (see --help)");
  Scene scene = loadSceneSpec(o.positional()[0]);
  applyEnvironmentOption(scene, o.text("--env", ""));
  std::cout << describeScene(scene);
  return 0;
}

int runExportScene(const Args& args) {
  if (wantsHelp(args)) {
    std::cout << "usage: photovr export-scene NAME OUT.glb|OUT.gltf\n"
                 "Writes a built-in scene (atrium, cornell, spheres) as glTF 2.0 so other tools\n"
                 "can open it. The procedural sky has no glTF form and is left out.\n";
    return 0;
  }
  const Options o(args, {}, {});
  if (o.positional().size() != 2)
    throw UsageError("export-scene: expected NAME and an output .glb/.gltf path (see --help)");
  const std::string& name = o.positional()[0];
  const std::string ext = std::filesystem::path(o.positional()[1]).extension().string();
  if (ext != ".glb" && ext != ".gltf")
    throw UsageError("export-scene: " + o.positional()[1] + ": expected a .glb or .gltf path");
  if (!isBuiltinScene(name)) makeBuiltinScene(name);  // throws the UsageError listing names
  const Scene scene = makeBuiltinScene(name);
  for (const std::string& w : writeGlb(scene, o.positional()[1]))
    std::cerr << "photovr: warning: " << w << "\n";
  std::cout << "wrote " << o.positional()[1] << "\n";
  return 0;
}

}  // namespace photovr::app
