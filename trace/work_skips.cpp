#include "trace/work_skips.h"

#include <sstream>
#include <stdexcept>

namespace photovr {

std::vector<std::string> WorkSkips::names() {
  return {"punctual-lights", "area-lights", "environment",  "any-hit",
          "refit",           "sky-pixels",  "dark-emitters"};
}

bool* WorkSkips::flag(const std::string& name) {
  if (name == "punctual-lights") return &punctualLights;
  if (name == "area-lights") return &areaLights;
  if (name == "environment") return &environment;
  if (name == "any-hit") return &anyHitFilter;
  if (name == "refit") return &refit;
  if (name == "sky-pixels") return &skyPixels;
  if (name == "dark-emitters") return &darkEmitters;
  return nullptr;
}

// "all" alone, or a comma-separated list of names.
void WorkSkips::disable(const std::string& list) {
  if (list == "all") {
    for (const std::string& n : names()) *flag(n) = false;
    return;
  }
  std::stringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    bool* f = flag(name);
    if (!f) {
      std::string known;
      for (const std::string& n : names()) known += (known.empty() ? "" : ", ") + n;
      throw std::invalid_argument("unknown skip '" + name + "' (expected 'all' alone, or of " +
                                  known + ")");
    }
    *f = false;
  }
}

}  // namespace photovr
