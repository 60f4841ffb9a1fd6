#include "core/options.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "core/error.h"

namespace photovr {
namespace {

float parseFloat(const std::string& option, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const float v = std::strtof(text.c_str(), &end);
  if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
    throw UsageError(option + ": '" + text + "' is not a finite number");
  return v;
}

}  // namespace

Options::Options(const std::vector<std::string>& args, const std::set<std::string>& valued,
                 const std::set<std::string>& flags) {
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.rfind("--", 0) != 0) {
      positional_.push_back(a);
      continue;
    }
    if (values_.count(a)) throw UsageError(a + ": given twice");
    if (flags.count(a)) {
      values_[a] = "";
    } else if (valued.count(a)) {
      if (i + 1 >= args.size()) throw UsageError(a + ": missing value");
      // An empty value is never meant: an empty --out would write into the root folder.
      if (args[i + 1].empty()) throw UsageError(a + ": empty value");
      values_[a] = args[++i];
    } else {
      throw UsageError("unknown option '" + a + "' (see --help)");
    }
  }
}

bool Options::has(const std::string& name) const {
  return values_.count(name) > 0;
}

std::string Options::text(const std::string& name, const std::string& fallback) const {
  auto it = values_.find(name);
  return it == values_.end() ? fallback : it->second;
}

int Options::integer(const std::string& name, int fallback, int min, int max) const {
  if (!has(name)) return fallback;
  const std::string& t = values_.at(name);
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(t.c_str(), &end, 10);
  if (t.empty() || *end != '\0' || errno == ERANGE)
    throw UsageError(name + ": '" + t + "' is not an integer");
  if (v < min || v > max)
    throw UsageError(name + ": " + t + " is out of range [" + std::to_string(min) + ", " +
                     std::to_string(max) + "]");
  return int(v);
}

float Options::number(const std::string& name, float fallback, float min, float max) const {
  if (!has(name)) return fallback;
  const float v = parseFloat(name, values_.at(name));
  if (v < min || v > max)
    throw UsageError(name + ": " + values_.at(name) + " is out of range [" + std::to_string(min) +
                     ", " + std::to_string(max) + "]");
  return v;
}

std::optional<glm::vec3> Options::vec3(const std::string& name) const {
  if (!has(name)) return std::nullopt;
  const std::string& t = values_.at(name);
  glm::vec3 v;
  size_t start = 0;
  for (int k = 0; k < 3; ++k) {
    const size_t comma = t.find(',', start);
    if ((k < 2) != (comma != std::string::npos))
      throw UsageError(name + ": '" + t + "' is not three comma-separated numbers X,Y,Z");
    v[k] = parseFloat(name, t.substr(start, comma == std::string::npos ? comma : comma - start));
    start = comma + 1;
  }
  return v;
}

std::string Options::choice(const std::string& name, const std::string& fallback,
                            const std::vector<std::string>& choices) const {
  const std::string v = text(name, fallback);
  for (const std::string& c : choices)
    if (c == v) return v;
  std::string list;
  for (const std::string& c : choices) list += (list.empty() ? "" : ", ") + c;
  throw UsageError(name + ": '" + v + "' is not one of " + list);
}

}  // namespace photovr
