#include "gl/shader_source.h"

#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "gl/context.h"
#include "shaders/embedded.h"

namespace photovr::gl {
namespace {

std::string rawSource(const std::string& name) {
  if (const char* dir = std::getenv("PHOTOVR_SHADER_DIR")) {
    std::ifstream in(std::string(dir) + "/" + name);
    if (!in) throw ContextError(std::string(dir) + "/" + name + ": shader file not found");
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  for (unsigned i = 0; i < shaders::kEmbeddedCount; ++i)
    if (name == shaders::kEmbedded[i].name) return shaders::kEmbedded[i].source;
  throw ContextError("shader '" + name + "' is not embedded in this build");
}

void expand(const std::string& name, std::set<std::string>& seen, std::string& out) {
  if (!seen.insert(name).second) return;
  std::istringstream in(rawSource(name));
  std::string line;
  while (std::getline(in, line)) {
    const auto pos = line.find("#include \"");
    if (pos == 0) {
      const auto end = line.find('"', 10);
      expand(line.substr(10, end - 10), seen, out);
    } else {
      out += line;
      out += '\n';
    }
  }
}

}  // namespace

std::string shaderSource(const std::string& name) {
  std::set<std::string> seen;
  std::string out;
  expand(name, seen, out);
  return out;
}

}  // namespace photovr::gl
