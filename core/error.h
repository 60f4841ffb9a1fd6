// One error policy (../shared/STYLE.md, 12): bad input and I/O throw InputError whose
// message is one line, "<file>: <problem>"; broken invariants are asserts.
#pragma once

#include <stdexcept>
#include <string>

namespace photovr {

class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& problem)
      : std::runtime_error(file.empty() ? problem : file + ": " + problem) {}
};

// A bad command-line argument; the message names the option and what was expected.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace photovr
