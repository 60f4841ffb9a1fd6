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
#include "core/options.h"

namespace photovr {

// A UsageError listing the built-in scenes unless 'name' is one.
inline std::string builtinSceneArgument(const std::string& name) {
  if (!isBuiltinScene(name)) makeBuiltinScene(name);  // throws the UsageError
  return name;
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
