// Runs the photovr binary the build produced and captures its exit status and output.
#pragma once

#include <string>

namespace photovr::testing {

struct CommandResult {
  int status = -1;     // exit status
  std::string output;  // stdout and stderr together
};

// A shell command line, stdout and stderr together.
CommandResult runCommand(const std::string& command);

// 'args' is appended to the binary's path as is (shell syntax); 'prefix' goes before it
// (e.g. "env -u NAME").
CommandResult runPhotovr(const std::string& args, const std::string& prefix = "");

std::string tempDir(const std::string& name);  // a fresh, empty folder for one test

}  // namespace photovr::testing
