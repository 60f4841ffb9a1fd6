// One error policy (../shared/STYLE.md, 12): bad input and I/O throw InputError whose
// message is one line, "<file>: <problem>"; broken invariants are asserts.
#pragma once

#include <stdexcept>
#include <string>

namespace photovr {

// 'text' with what a terminal line should not hold written as \xNN: control characters
// (a line break among them) and bytes that are not UTF-8. A problem may quote the file's own
// bytes (a parser's "last read: ..."), and a binary file's would garble the line.
std::string printableLine(const std::string& text);

class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& problem)
      : std::runtime_error(file.empty() ? printableLine(problem)
                                        : file + ": " + printableLine(problem)) {}
};

// A bad command-line argument; the message names the option and what was expected.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace photovr
