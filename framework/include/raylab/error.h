// raylab/error.h: the one exception type for bad input.
#pragma once

#include <stdexcept>
#include <string>

namespace raylab {

/// Bad input: a malformed file, an invalid parameter, an impossible request. what() is
/// one line that names the problem and, where there is one, the file and line
/// (docs/style.md rule 10).
class Error : public std::runtime_error {
  public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace raylab
