// Command-line parsing: "--name value" and "--flag" pairs after a subcommand, with typed,
// range-checked getters. Every problem is a UsageError naming the option.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace photovr {

class Options {
 public:
  // 'valued' options take a value, 'flags' do not; anything else is an error.
  Options(const std::vector<std::string>& args, const std::set<std::string>& valued,
          const std::set<std::string>& flags);

  bool has(const std::string& name) const;
  std::string text(const std::string& name, const std::string& fallback) const;
  int integer(const std::string& name, int fallback, int min, int max) const;
  float number(const std::string& name, float fallback, float min, float max) const;
  std::optional<glm::vec3> vec3(const std::string& name) const;  // "x,y,z"
  // One of 'choices', else UsageError listing them.
  std::string choice(const std::string& name, const std::string& fallback,
                     const std::vector<std::string>& choices) const;
  const std::vector<std::string>& positional() const { return positional_; }

 private:
  std::map<std::string, std::string> values_;
  std::vector<std::string> positional_;
};

}  // namespace photovr
