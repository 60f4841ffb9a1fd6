#include "tests/app/cli_util.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>

namespace photovr::testing {

CommandResult runCommand(const std::string& command) {
  CommandResult r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
  const int raw = pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
  return r;
}

CommandResult runPhotovr(const std::string& args, const std::string& prefix) {
  return runCommand(prefix + " " + std::string(PHOTOVR_BINARY) + " " + args);
}

std::string tempDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("photovr-test-" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

}  // namespace photovr::testing
