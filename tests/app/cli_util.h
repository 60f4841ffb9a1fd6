// Runs the photovr binary the build produced and captures its exit status and output.
#pragma once

#include <string>

namespace photovr::testing {

struct CommandResult {
  int status = -1;     // exit status
  std::string output;  // stdout and stderr together
};

// 'args' is appended to the binary's path as is (shell syntax).
CommandResult runPhotovr(const std::string& args);

std::string tempDir(const std::string& name);  // a fresh, empty folder for one test

}  // namespace photovr::testing
