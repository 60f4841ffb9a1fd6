// The bench tools' command lines: core/options.h's "--name value" parsing with typed,
// range-checked getters, "--help", and photovr's error policy (a usage error is one line
// and exit 2, any other failure one line and exit 1).
#pragma once

#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "core/builtin_scenes.h"
#include "core/error.h"
#include "core/gltf_loader.h"
#include "core/options.h"

namespace photovr {

// A UsageError listing the built-in scenes unless 'name' is one.
inline std::string builtinSceneArgument(const std::string& name) {
  if (!isBuiltinScene(name)) makeBuiltinScene(name);  // throws the UsageError
  return name;
}

// 'spec' if it is a built-in scene's name or an existing .gltf/.glb file; else a UsageError.
inline std::string sceneArgument(const std::string& spec) {
  if (isBuiltinScene(spec)) return spec;
  const std::string ext = std::filesystem::path(spec).extension().string();
  if (ext == ".gltf" || ext == ".glb") {
    if (!std::filesystem::is_regular_file(spec))
      throw UsageError("--scene: no such file '" + spec + "'");
    return spec;
  }
  return builtinSceneArgument(spec);  // throws the UsageError listing the built-in scenes
}

// The scenes a bench runs: every built-in one, or the one 'spec' names (sceneArgument).
inline std::vector<std::string> benchSceneNames(const std::string& spec) {
  return spec.empty() ? builtinSceneNames() : std::vector<std::string>{spec};
}

// A built-in scene by name, or a glTF file (its warnings to stderr).
inline Scene loadBenchScene(const std::string& spec) {
  if (isBuiltinScene(spec)) return makeBuiltinScene(spec);
  Scene scene = loadGltf(spec);
  for (const std::string& w : scene.warnings)
    std::fprintf(stderr, "%s: warning: %s\n", spec.c_str(), w.c_str());
  return scene;
}

// Runs 'run' on argv's options ('valued' take a value, 'flags' do not); "--help" prints
// 'usage' instead.
inline int benchMain(int argc, char** argv, const char* usage, const std::set<std::string>& valued,
                     const std::set<std::string>& flags,
                     const std::function<int(const Options&)>& run) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  const std::string tool = std::filesystem::path(argv[0]).filename().string();
  for (const std::string& a : args)
    if (a == "--help" || a == "-h") {
      std::fputs(usage, stdout);
      return 0;
    }
  try {
    const Options options(args, valued, flags);
    if (!options.positional().empty())
      throw UsageError("unexpected argument '" + options.positional()[0] + "' (see --help)");
    return run(options);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "%s: %s\n", tool.c_str(), e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", tool.c_str(), e.what());
    return 1;
  }
}

}  // namespace photovr
