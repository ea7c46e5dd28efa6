#pragma once
// Errors that reach the user as one line and exit code 2 (bad scene file, bad flag, bad path).
#include <stdexcept>
#include <string>

namespace dampbound {

/// Bad input: the message names the file and line, or the flag. The CLI prints it on one line
/// and exits with code 2.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace dampbound
