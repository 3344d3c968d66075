#pragma once
// The one exception type for bad input (case files, recordings, meshing requests, singular systems).
// Its message is a single line: where (file / field), the value, the constraint, and the fix.
#include <stdexcept>
#include <string>

namespace sw {

class InputError : public std::runtime_error {
public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace sw
