// photovr: photorealistic stereo rendering for VR. Thin front end over the modules.
#include <cstdio>
#include <iostream>
#include <map>

#include "app/commands.h"
#include "core/error.h"
#include "core/huge_pages.h"
#include "gl/context.h"

namespace {

// The commands that render frames re-execute with malloc on huge pages (core/huge_pages.h);
// the others, and --help, are not worth a second start-up.
void hugePagesForFrames(int argc, char** argv, char** envp) {
  const std::string command = argc >= 2 ? argv[1] : "";
  for (int i = 2; i < argc; ++i)
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") return;
  if (command == "render" || command == "view" || command == "ab" || command == "reference" ||
      command == "stress" || command == "bench")
    photovr::useHugePagesForMalloc(argc, argv, envp);
}

}  // namespace

PHOTOVR_PREINIT(hugePagesForFrames);

namespace {

const char* const kUsage =
    "usage: photovr COMMAND [options]   (photovr COMMAND --help for its options)\n"
    "commands:\n"
    "  render        render a scene headless and write the images\n"
    "  info          print what a scene contains and what the renderer will use\n"
    "  export-scene  write a built-in scene as glTF 2.0\n"
    "  ab            hybrid vs pure path tracing against a converged reference\n"
    "  reference     render or extend the cached converged reference of a scene\n"
    "  stress        run the numerical stress suite and print its report\n"
    "  bench         run time against error of hybrid and pt on the built-in scenes\n"
    "  view          interactive window: the headset's panel image, re-projected every\n"
    "                refresh, with an overlay (DK2, replay, pose script or desktop camera)\n";

using Command = int (*)(const photovr::app::Args&);

int dispatch(int argc, char** argv) {
  const std::map<std::string, Command> commands = {{"render", photovr::app::runRender},
                                                   {"info", photovr::app::runInfo},
                                                   {"export-scene", photovr::app::runExportScene},
                                                   {"ab", photovr::app::runAb},
                                                   {"reference", photovr::app::runReference},
                                                   {"stress", photovr::app::runStress},
                                                   {"bench", photovr::app::runBench},
                                                   {"view", photovr::app::runView}};
  if (argc < 2) {
    std::cerr << kUsage;
    return 2;
  }
  const std::string name = argv[1];
  if (name == "--help" || name == "-h" || name == "help") {
    std::cout << kUsage;
    return 0;
  }
  auto it = commands.find(name);
  if (it == commands.end()) {
    std::string names;
    for (const auto& [command, run] : commands) names += (names.empty() ? "" : ", ") + command;
    throw photovr::UsageError("unknown command '" + name + "' (expected one of " + names + ")");
  }
  return it->second(photovr::app::Args(argv + 2, argv + argc));
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return dispatch(argc, argv);
  } catch (const photovr::UsageError& e) {
    std::cerr << "photovr: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {  // InputError, gl::ContextError, I/O
    std::cerr << "photovr: " << e.what() << "\n";
    return 1;
  }
}
