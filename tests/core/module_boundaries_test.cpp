// One API per directory (../shared/STYLE.md, 2): OpenGL calls only in gl/, Embree calls
// only in trace/, hidapi calls only in hmd/. Scans the source tree this test was built from.
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>

namespace {

namespace fs = std::filesystem;

std::vector<std::string> violations(const std::regex& call, const std::string& home) {
  std::vector<std::string> found;
  const fs::path root(PHOTOVR_SOURCE_DIR);
  for (const char* dir : {"core", "gl", "trace", "hybrid", "hmd", "app", "bench"}) {
    if (dir == home || !fs::exists(root / dir)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root / dir)) {
      const std::string ext = entry.path().extension().string();
      if (ext != ".cpp" && ext != ".h") continue;
      std::ifstream in(entry.path());
      std::stringstream ss;
      ss << in.rdbuf();
      if (std::regex_search(ss.str(), call)) found.push_back(entry.path().string());
    }
  }
  return found;
}

TEST(ModuleBoundaries, OpenGLCallsOnlyInGl) {
  EXPECT_EQ(violations(std::regex(R"(\bgl[A-Z][a-zA-Z]+\()"), "gl"), std::vector<std::string>{});
}

TEST(ModuleBoundaries, EmbreeCallsOnlyInTrace) {
  EXPECT_EQ(violations(std::regex(R"(\brtc[A-Z][a-zA-Z]+\()"), "trace"), std::vector<std::string>{});
}

TEST(ModuleBoundaries, HidapiCallsOnlyInHmd) {
  EXPECT_EQ(violations(std::regex(R"(\bhid_[a-z_]+\()"), "hmd"), std::vector<std::string>{});
}

}  // namespace
