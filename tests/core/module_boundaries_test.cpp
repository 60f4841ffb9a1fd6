// One API per directory (../shared/STYLE.md, 2): OpenGL calls only in gl/, Embree calls
// only in trace/, hidapi calls only in hmd/. Scans the source tree this test was built from.
#include <filesystem>
#include <fstream>
#include <cctype>
#include <sstream>

#include <gtest/gtest.h>

namespace {

namespace fs = std::filesystem;

// True when 'text' calls a function named prefix + [A-Z or a-z_ per 'upper'] + letters,
// i.e. "glClear(", "rtcIntersect1(", "hid_open(" — at a word start. (Hand-written rather than
// std::regex, whose GCC 12 headers trip -Wmaybe-uninitialized under the sanitizers.)
bool callsApi(const std::string& text, const std::string& prefix, bool upper) {
  for (size_t at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at + 1)) {
    if (at > 0 && (std::isalnum(uint8_t(text[at - 1])) || text[at - 1] == '_')) continue;
    size_t i = at + prefix.size();
    if (i >= text.size()) break;
    const char first = text[i];
    if (upper ? !std::isupper(uint8_t(first)) : !(std::islower(uint8_t(first)) || first == '_'))
      continue;
    while (i < text.size() && (std::isalnum(uint8_t(text[i])) || text[i] == '_')) ++i;
    if (i < text.size() && text[i] == '(') return true;
  }
  return false;
}

struct Api {
  std::string prefix;
  bool upper;
};

std::vector<std::string> violations(const Api& api, const std::string& home) {
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
      if (callsApi(ss.str(), api.prefix, api.upper)) found.push_back(entry.path().string());
    }
  }
  return found;
}

TEST(ModuleBoundaries, TheScannerFindsCallsAndNothingElse) {
  EXPECT_TRUE(callsApi("x = glClear(0);", "gl", true));
  EXPECT_TRUE(callsApi("rtcIntersect1(s, &c, &r);", "rtc", true));
  EXPECT_TRUE(callsApi("hid_open(0x2833, 0x21, 0);", "hid_", false));
  EXPECT_FALSE(callsApi("int glow(int); glm::vec3 v; gltf(x);", "gl", true));
  EXPECT_FALSE(callsApi("myglClear(0);", "gl", true));
  EXPECT_FALSE(callsApi("glClear;", "gl", true));
}

TEST(ModuleBoundaries, OpenGLCallsOnlyInGl) {
  EXPECT_EQ(violations({"gl", true}, "gl"), std::vector<std::string>{});
}

TEST(ModuleBoundaries, EmbreeCallsOnlyInTrace) {
  EXPECT_EQ(violations({"rtc", true}, "trace"), std::vector<std::string>{});
}

TEST(ModuleBoundaries, HidapiCallsOnlyInHmd) {
  EXPECT_EQ(violations({"hid_", false}, "hmd"), std::vector<std::string>{});
}

}  // namespace
