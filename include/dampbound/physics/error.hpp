#pragma once
// Errors that reach the user as one line and exit code 2 (bad scene file, bad flag, bad path).
// Core's one error idiom (docs/architecture.md): bad input throws InputError; a broken
// precondition of an API call (an array of the wrong size, an index out of range) throws
// std::invalid_argument or std::out_of_range as the standard library does; a question that
// may have no answer returns std::optional. No error codes, no "empty string means OK".
#include "dampbound/physics/export.hpp"
#include <stdexcept>
#include <string>

namespace dampbound DAMPBOUND_API {

/// Bad input: the message names the file and line, the flag or the parameter. The CLI prints
/// it on one line and exits with code 2.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace dampbound
